/* The ROS 1 intake's frame loop in C: length-prefixed rosgraph_msgs/Log messages, as they come
 * off a TCPROS socket, decoded into the columns of a ColumnsBuilder.
 *
 * Built on this machine the first time the live source needs it (compiled_frames.py). It does
 * what Ros1LogDecoder.decode_frames does in Python, for the messages that decoder would read
 * from its caches: a node name and a tail (file, function, line, topics) seen before. Every
 * other message (the first of a new node or log statement, one malformed, a length past
 * max_length) stops the loop there, and the Python decoder reads that one message (caching
 * its strings, refusing it, or raising) before calling the loop again: the rules for what is
 * readable live in one place, and a message the loop reads comes out as Python would read it.
 *
 * frames(buffer, pos, max_length, names, tails, levels_table, stamps, levels, nodes, msgs,
 *        tails_out) -> (pos, stopped)
 *   buffer        bytes (anything with the buffer protocol)
 *   pos           where the first frame starts
 *   names, tails  the decoder's caches: {name bytes: str}, {tail bytes: tuple} (only read)
 *   levels_table  a tuple of 256 levels, by ROS 1 level byte
 *   stamps ... tails_out   the builder's lists, appended to
 *   pos           where the loop stopped: the first frame not read
 *   stopped       false: the frame at pos is incomplete (or none is left);
 *                 true: the frame at pos is for the Python decoder
 * Nothing is read past a frame's end: every length is checked against it first. The GIL is
 * held throughout: a call is bounded by the buffer's size.
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <stdint.h>
#include <string.h>

/* seq, stamp, four string lengths, level, two more lengths, line, topic count (MIN_LENGTH). */
#define MIN_LENGTH (12 + 4 + 1 + 4 * 4 + 4 + 4)

static uint32_t u32(const unsigned char *p) {
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}

/* A cache's value for the bytes [p, p + n): the last one found when the bytes are the same
 * (a flood repeats them), else looked up in `cache` (borrowed; NULL if absent or on error). */
typedef struct {
    const unsigned char *bytes;
    Py_ssize_t size;
    PyObject *value; /* borrowed from the cache, which the caller holds */
} Memo;

static PyObject *cached(PyObject *cache, Memo *memo, const unsigned char *p, Py_ssize_t n) {
    if (memo->value != NULL && memo->size == n && memcmp(memo->bytes, p, (size_t)n) == 0) {
        return memo->value;
    }
    PyObject *key = PyBytes_FromStringAndSize((const char *)p, n);
    if (key == NULL) {
        return NULL;
    }
    PyObject *value = PyDict_GetItemWithError(cache, key); /* borrowed */
    Py_DECREF(key);
    if (value != NULL) {
        memo->bytes = p;
        memo->size = n;
        memo->value = value;
    }
    return value;
}

static int append_new(PyObject *list, PyObject *item) {
    if (item == NULL) {
        return -1;
    }
    int failed = PyList_Append(list, item);
    Py_DECREF(item);
    return failed;
}

static PyObject *frames(PyObject *self, PyObject *args) {
    Py_buffer view;
    Py_ssize_t start, max_length;
    PyObject *names, *tails, *levels_table, *stamps, *levels, *nodes, *msgs, *tails_out;
    (void)self;
    if (!PyArg_ParseTuple(args, "y*nnO!O!O!O!O!O!O!O!", &view, &start, &max_length, &PyDict_Type, &names,
                          &PyDict_Type, &tails, &PyTuple_Type, &levels_table, &PyList_Type, &stamps, &PyList_Type,
                          &levels, &PyList_Type, &nodes, &PyList_Type, &msgs, &PyList_Type, &tails_out)) {
        return NULL;
    }
    if (PyTuple_GET_SIZE(levels_table) != 256 || start < 0) {
        PyBuffer_Release(&view);
        PyErr_SetString(PyExc_ValueError, "levels_table must hold 256 levels; pos must not be negative");
        return NULL;
    }
    const unsigned char *buffer = (const unsigned char *)view.buf;
    const uint64_t size = (uint64_t)view.len;
    uint64_t pos = (uint64_t)start;
    int stopped = 0;
    Memo name_memo = {NULL, 0, NULL};
    Memo tail_memo = {NULL, 0, NULL};
    while (pos + 4 <= size) {
        const uint64_t length = u32(buffer + pos);
        if (length > (uint64_t)max_length || length < MIN_LENGTH) {
            stopped = length <= (uint64_t)max_length ? pos + 4 + length <= size : 1;
            break;
        }
        const uint64_t begin = pos + 4;
        const uint64_t end = begin + length;
        if (end > size) {
            break;
        }
        stopped = 1; /* until this frame is read */
        const uint32_t secs = u32(buffer + begin + 4);
        const uint32_t nsecs = u32(buffer + begin + 8);
        uint64_t p = begin + 16 + (uint64_t)u32(buffer + begin + 12); /* past frame_id */
        if (p + 5 > end) {
            break;
        }
        const unsigned char level = buffer[p];
        uint64_t n = u32(buffer + p + 1);
        p += 5;
        if (p + n + 4 > end) {
            break;
        }
        PyObject *name = cached(names, &name_memo, buffer + p, (Py_ssize_t)n);
        if (name == NULL) {
            if (PyErr_Occurred()) {
                goto fail;
            }
            break;
        }
        p += n;
        n = u32(buffer + p);
        p += 4;
        if (p + n > end) {
            break;
        }
        const uint64_t msg_at = p, msg_size = n;
        p += n;
        PyObject *tail = cached(tails, &tail_memo, buffer + p, (Py_ssize_t)(end - p));
        if (tail == NULL) {
            if (PyErr_Occurred()) {
                goto fail;
            }
            break;
        }
        PyObject *msg = PyUnicode_DecodeUTF8((const char *)buffer + msg_at, (Py_ssize_t)msg_size, "replace");
        if (msg == NULL) {
            goto fail;
        }
        /* the stamp first: a list that fails to grow leaves the columns as they were */
        if (append_new(stamps, PyLong_FromUnsignedLongLong((unsigned long long)secs * 1000000000ULL + nsecs)) < 0) {
            Py_DECREF(msg);
            goto fail;
        }
        if (PyList_Append(levels, PyTuple_GET_ITEM(levels_table, level)) < 0 || PyList_Append(nodes, name) < 0 ||
            append_new(msgs, msg) < 0 || PyList_Append(tails_out, tail) < 0) {
            goto fail;
        }
        stopped = 0;
        pos = end;
    }
    PyBuffer_Release(&view);
    return Py_BuildValue("(nO)", (Py_ssize_t)pos, stopped ? Py_True : Py_False);

fail:
    PyBuffer_Release(&view);
    return NULL;
}

static PyMethodDef methods[] = {
    {"frames", frames, METH_VARARGS,
     "frames(buffer, pos, max_length, names, tails, levels_table, stamps, levels, nodes, msgs, tails_out) -> (pos, "
     "stopped)"},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef module = {PyModuleDef_HEAD_INIT, "console_tui_frame_loop", NULL, -1, methods, NULL, NULL, NULL, NULL};

PyMODINIT_FUNC PyInit_console_tui_frame_loop(void) { return PyModule_Create(&module); }
