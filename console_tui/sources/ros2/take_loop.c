/* The intake's take loop in C: serialized messages taken from one rcl subscription.
 *
 * Built on this machine the first time the live source needs it (compiled_take.py), against
 * the headers of the rcl that rclpy loaded. Python's own loop pays for a pybind11 call, a
 * message-info dict and a sequence-number check a message; this loop pays for the take and
 * one bytes object.
 *
 * take(pointer, limit, last_seen[, infos]) -> (messages, lost)
 *   pointer    the address of an rcl_subscription_t (rclpy's Subscription.pointer)
 *   limit      how many messages to take at most
 *   last_seen  {publisher GID bytes: highest sequence number seen}, read and updated
 *   infos      a list, or None: given a list, each message's info is appended to it as
 *              rclpy gives it ({"publisher_gid": bytes, "publication_sequence_number": int})
 *              and the sequence numbers are left to the caller (last_seen untouched, lost 0):
 *              the extra subscription keeps only some messages, and checks those
 *   messages   the serialized messages, oldest first (a list of bytes)
 *   lost       messages the gaps in each publisher's sequence numbers show were lost
 *              (the same rule as SequenceGaps.see in loss_counts.py)
 * The GIL is held throughout: a call is bounded by `limit`.
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <stdint.h>
#include <string.h>

#include <rcl/subscription.h>
#include <rcutils/error_handling.h>
#include <rcutils/types/uint8_array.h>

#define GID_SIZE sizeof(((rmw_gid_t *)0)->data)

/* The publisher whose messages are being taken, and the highest number seen from it. */
typedef struct {
    uint8_t gid[GID_SIZE];
    uint64_t last;
    int known; /* a publisher is loaded */
    int seen;  /* `last` holds a number */
} Publisher;

static int store_last(PyObject *last_seen, const Publisher *publisher) {
    if (!publisher->known || !publisher->seen) {
        return 0;
    }
    PyObject *key = PyBytes_FromStringAndSize((const char *)publisher->gid, GID_SIZE);
    PyObject *value = PyLong_FromUnsignedLongLong(publisher->last);
    int failed = key == NULL || value == NULL || PyDict_SetItem(last_seen, key, value) < 0;
    Py_XDECREF(key);
    Py_XDECREF(value);
    return failed ? -1 : 0;
}

static int load_publisher(PyObject *last_seen, Publisher *publisher, const uint8_t *gid) {
    memcpy(publisher->gid, gid, GID_SIZE);
    publisher->known = 1;
    publisher->seen = 0;
    PyObject *key = PyBytes_FromStringAndSize((const char *)gid, GID_SIZE);
    if (key == NULL) {
        return -1;
    }
    PyObject *value = PyDict_GetItemWithError(last_seen, key); /* borrowed */
    Py_DECREF(key);
    if (value == NULL) {
        return PyErr_Occurred() ? -1 : 0;
    }
    unsigned long long last = PyLong_AsUnsignedLongLong(value);
    if (last == (unsigned long long)-1 && PyErr_Occurred()) {
        return -1;
    }
    publisher->last = last;
    publisher->seen = 1;
    return 0;
}

static PyObject *take(PyObject *self, PyObject *args) {
    unsigned long long pointer;
    Py_ssize_t limit;
    PyObject *last_seen;
    PyObject *infos = Py_None;
    (void)self;
    if (!PyArg_ParseTuple(args, "KnO!|O", &pointer, &limit, &PyDict_Type, &last_seen, &infos)) {
        return NULL;
    }
    if (infos != Py_None && !PyList_Check(infos)) {
        PyErr_SetString(PyExc_TypeError, "infos must be a list or None");
        return NULL;
    }
    const rcl_subscription_t *subscription = (const rcl_subscription_t *)(uintptr_t)pointer;
    rcutils_allocator_t allocator = rcutils_get_default_allocator();
    rcutils_uint8_array_t buffer = rcutils_get_zero_initialized_uint8_array();
    if (rcutils_uint8_array_init(&buffer, 4096, &allocator) != RCUTILS_RET_OK) {
        rcutils_reset_error();
        return PyErr_NoMemory();
    }
    PyObject *messages = PyList_New(0);
    Publisher publisher = {{0}, 0, 0, 0};
    unsigned long long lost = 0;
    const char *problem = NULL;
    char why[sizeof(rcutils_error_string_t) + 64];
    if (messages == NULL) {
        goto fail;
    }
    for (Py_ssize_t count = 0; count < limit; count++) {
        rmw_message_info_t info = rmw_get_zero_initialized_message_info();
        rcl_ret_t ret = rcl_take_serialized_message(subscription, &buffer, &info, NULL);
        if (ret == RCL_RET_SUBSCRIPTION_TAKE_FAILED) {
            rcutils_reset_error();
            break;
        }
        if (ret != RCL_RET_OK) {
            snprintf(why, sizeof why, "rcl_take_serialized_message: %s", rcutils_get_error_string().str);
            rcutils_reset_error();
            if (PyList_GET_SIZE(messages) > 0) {
                break; /* keep what was taken; the next call reports the problem */
            }
            problem = why;
            goto fail;
        }
        PyObject *message = PyBytes_FromStringAndSize((const char *)buffer.buffer, (Py_ssize_t)buffer.buffer_length);
        if (message == NULL || PyList_Append(messages, message) < 0) {
            Py_XDECREF(message);
            goto fail;
        }
        Py_DECREF(message);
        uint64_t number = info.publication_sequence_number;
        if (number == RMW_MESSAGE_INFO_SEQUENCE_NUMBER_UNSUPPORTED) {
            number = 0;
        }
        if (infos != Py_None) {
            PyObject *entry = Py_BuildValue(
                "{s:y#,s:K}", "publisher_gid", (const char *)info.publisher_gid.data, (Py_ssize_t)GID_SIZE,
                "publication_sequence_number", (unsigned long long)number);
            if (entry == NULL || PyList_Append(infos, entry) < 0) {
                Py_XDECREF(entry);
                goto fail;
            }
            Py_DECREF(entry);
            continue;
        }
        if (number == 0) {
            continue;
        }
        if (!publisher.known || memcmp(publisher.gid, info.publisher_gid.data, GID_SIZE) != 0) {
            if (store_last(last_seen, &publisher) < 0 || load_publisher(last_seen, &publisher, info.publisher_gid.data) < 0) {
                goto fail;
            }
        }
        if (!publisher.seen || number > publisher.last) {
            if (publisher.seen && number > publisher.last + 1) {
                lost += number - publisher.last - 1;
            }
            publisher.last = number;
            publisher.seen = 1;
        }
    }
    if (store_last(last_seen, &publisher) < 0) {
        goto fail;
    }
    if (rcutils_uint8_array_fini(&buffer) != RCUTILS_RET_OK) {
        rcutils_reset_error();
    }
    return Py_BuildValue("(NK)", messages, lost);

fail:
    Py_XDECREF(messages);
    if (rcutils_uint8_array_fini(&buffer) != RCUTILS_RET_OK) {
        rcutils_reset_error();
    }
    if (problem != NULL) {
        PyErr_SetString(PyExc_RuntimeError, problem);
    }
    return NULL;
}

static PyMethodDef methods[] = {
    {"take", take, METH_VARARGS, "take(pointer, limit, last_seen[, infos]) -> (messages, lost)"},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef module = {PyModuleDef_HEAD_INIT, "console_tui_take_loop", NULL, -1, methods, NULL, NULL, NULL, NULL};

PyMODINIT_FUNC PyInit_console_tui_take_loop(void) { return PyModule_Create(&module); }
