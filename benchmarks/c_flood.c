/* A publisher's loop in C for benchmarks/intake.py (``--publisher c``).
 *
 *   flood(pointer, pool, rate, duration) -> (sent, failed, elapsed)
 *
 *   pointer   the address of an rcl_publisher_t (rclpy's Publisher.handle.pointer)
 *   pool      a list of bytes: serialized messages, published in turn
 *   rate      messages a second (0 or less: as fast as it can)
 *   duration  seconds to publish for
 *
 * Publishes with rcl_publish_serialized_message, the GIL released, paced as the Python
 * publisher paces (what is due by now, then 0.5 ms of sleep). It stands for a node written in
 * C++, whose log calls reach /rosout through rcl without Python's share of the cost (about 3
 * of rclpy's 10 us a message on the project's machines; rcl and Fast DDS take the rest).
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <stdint.h>
#include <time.h>

#include <rcl/publisher.h>
#include <rcutils/error_handling.h>
#include <rcutils/types/uint8_array.h>

static double now_s(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec / 1e9;
}

static PyObject *flood(PyObject *self, PyObject *args) {
    unsigned long long pointer;
    PyObject *pool;
    double rate, duration;
    (void)self;
    if (!PyArg_ParseTuple(args, "KO!dd", &pointer, &PyList_Type, &pool, &rate, &duration)) {
        return NULL;
    }
    Py_ssize_t count = PyList_GET_SIZE(pool);
    if (count == 0) {
        PyErr_SetString(PyExc_ValueError, "an empty pool");
        return NULL;
    }
    rcl_serialized_message_t *messages = PyMem_Calloc((size_t)count, sizeof *messages);
    if (messages == NULL) {
        return PyErr_NoMemory();
    }
    for (Py_ssize_t i = 0; i < count; ++i) {
        PyObject *item = PyList_GET_ITEM(pool, i);
        if (!PyBytes_Check(item)) {
            PyMem_Free(messages);
            PyErr_SetString(PyExc_TypeError, "the pool holds bytes");
            return NULL;
        }
        messages[i].buffer = (uint8_t *)PyBytes_AS_STRING(item);
        messages[i].buffer_length = (size_t)PyBytes_GET_SIZE(item);
        messages[i].buffer_capacity = messages[i].buffer_length;
    }
    const rcl_publisher_t *publisher = (const rcl_publisher_t *)(uintptr_t)pointer;
    long long sent = 0, failed = 0;
    double start, end, now;
    Py_BEGIN_ALLOW_THREADS
    start = now_s();
    end = start + duration;
    now = start;
    while (now < end) {
        long long due = rate > 0 ? (long long)((now - start) * rate) : sent + failed + 100;
        while (sent + failed < due) {
            rcl_serialized_message_t *message = &messages[(sent + failed) % count];
            if (rcl_publish_serialized_message(publisher, message, NULL) == RCL_RET_OK) {
                ++sent;
            } else {  /* Fast DDS refuses when its history is full of unacknowledged messages */
                rcutils_reset_error();
                ++failed;
            }
        }
        if (rate > 0) {
            struct timespec pause = {0, 500000};
            nanosleep(&pause, NULL);
        }
        now = now_s();
    }
    Py_END_ALLOW_THREADS
    PyMem_Free(messages);
    return Py_BuildValue("(LLd)", sent, failed, now - start);
}

static PyMethodDef methods[] = {
    {"flood", flood, METH_VARARGS, "flood(pointer, pool, rate, duration) -> (sent, failed, elapsed)"},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef module = {PyModuleDef_HEAD_INIT, "c_flood", NULL, -1, methods};

PyMODINIT_FUNC PyInit_c_flood(void) { return PyModule_Create(&module); }
