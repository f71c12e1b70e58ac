/* Reading ROS 2 node log lines in rcutils' default format at C speed, for the file index.
 *
 * scan(data, start, end, max_records, nodes, new_names, want_messages, at_eof)
 *
 * reads the records of data[start:end], where start is where a record begins (or the
 * start of the file), as rcutils' default template writes them:
 *
 *     [SEVERITY] [SECONDS.NANOSECONDS] [NAME]: MESSAGE
 *
 * with the lines after it that are no such line continuing its message. It reads only what
 * it can read exactly as the Python reader (console_tui/model/formats/rcutils_log.py) does:
 * ASCII digits, valid UTF-8, no NUL, no ESC (colour), lines and records of bounded size. At
 * the first line that is not plainly one or the other it stops ("irregular") and the
 * Python reader reads from the start of the record that line is in.
 *
 * Returns (status, stop, count, lines, stamps, levels, node_ids, messages, starts):
 *   status 0: max_records records read; stop is where the next one begins;
 *   status 1: the end was reached: with at_eof the last record ends there; otherwise the
 *             last record (which may go on past end) is not counted and stop is its start;
 *   status 2: irregular: stop is the start of the record the line is in (or the line,
 *             before any record); the records before it are returned.
 * lines: the newlines in data[start:stop]; stamps: int64 each, levels: uint8 each, node_ids: uint32 each (ids in the dict nodes,
 * name bytes -> id; a new name gets the next id and is appended to the list new_names),
 * messages: with want_messages the messages' UTF-8 joined by NUL, and starts: uint32 each,
 * count + 1 of them, where each message begins in characters (the last: the length + 1);
 * else None and None.
 */
#define PY_SSIZE_T_CLEAN
#ifndef _GNU_SOURCE
#define _GNU_SOURCE /* memmem */
#endif
#include <Python.h>
#include <stdint.h>
#include <string.h>

#define MAX_LINE_BYTES (1 << 20)
#define MAX_RECORD_BYTES (1 << 20)
#define MAX_RECORD_LINES 10000
#define MAX_SECONDS 9223372035LL

/* The names met in one call, so that a name costs a Python lookup only once a call. */
#define CACHE_SLOTS 1024
typedef struct {
    const unsigned char *name;
    Py_ssize_t length;
    uint32_t hash, ident;
} Slot;

static uint32_t hash_of(const unsigned char *bytes, Py_ssize_t length) {
    uint32_t hash = 2166136261u;
    for (Py_ssize_t i = 0; i < length; i++)
        hash = (hash ^ bytes[i]) * 16777619u;
    return hash;
}

typedef struct {
    char *data;
    Py_ssize_t size, used;
} Buffer;

static int grow(Buffer *buffer, Py_ssize_t more) {
    if (buffer->used + more <= buffer->size)
        return 0;
    Py_ssize_t size = buffer->size ? buffer->size : 4096;
    while (size < buffer->used + more)
        size *= 2;
    char *data = PyMem_RawRealloc(buffer->data, size);
    if (data == NULL)
        return -1; /* (the caller says so, holding the GIL) */
    buffer->data = data;
    buffer->size = size;
    return 0;
}

static int put(Buffer *buffer, const void *bytes, Py_ssize_t length) {
    if (grow(buffer, length) < 0)
        return -1;
    memcpy(buffer->data + buffer->used, bytes, length);
    buffer->used += length;
    return 0;
}

/* The message of the record ending at data[end] (its last newline) goes to messages, NUL after
 * it, and where the next begins (in characters) to starts. */
static int end_message(Buffer *messages, Buffer *starts, const unsigned char *data, Py_ssize_t from, Py_ssize_t end,
                       Py_ssize_t *chars, Py_ssize_t record_chars) {
    unsigned char nul = 0;
    *chars += record_chars + 1;
    uint32_t next = (uint32_t)*chars;
    if (put(messages, data + from, end - from) < 0 || put(messages, &nul, 1) < 0 || put(starts, &next, 4) < 0)
        return -1;
    return 0;
}

/* Whether line[0:length] is valid UTF-8 (as Python's strict decoder has it) with no NUL or
 * ESC; adds its characters to *chars. */
static int plain_utf8(const unsigned char *line, Py_ssize_t length, Py_ssize_t *chars) {
    Py_ssize_t i = 0, count = 0;
    while (i < length) {
        if (i + 8 <= length) { /* eight ASCII bytes at once, none NUL or ESC */
            uint64_t word;
            memcpy(&word, line + i, 8);
            uint64_t esc = word ^ 0x1b1b1b1b1b1b1b1bULL;
            uint64_t zero = (word - 0x0101010101010101ULL) & ~word & 0x8080808080808080ULL;
            uint64_t escaped = (esc - 0x0101010101010101ULL) & ~esc & 0x8080808080808080ULL;
            if ((word & 0x8080808080808080ULL) == 0 && zero == 0 && escaped == 0) {
                i += 8;
                count += 8;
                continue;
            }
        }
        unsigned char c = line[i];
        if (c < 0x80) {
            if (c == 0 || c == 0x1b)
                return 0;
            i++;
        } else if (c >= 0xc2 && c <= 0xdf) {
            if (i + 1 >= length || (line[i + 1] & 0xc0) != 0x80)
                return 0;
            i += 2;
        } else if (c >= 0xe0 && c <= 0xef) {
            if (i + 2 >= length || (line[i + 1] & 0xc0) != 0x80 || (line[i + 2] & 0xc0) != 0x80)
                return 0;
            if (c == 0xe0 && line[i + 1] < 0xa0)
                return 0; /* overlong */
            if (c == 0xed && line[i + 1] >= 0xa0)
                return 0; /* a surrogate */
            i += 3;
        } else if (c >= 0xf0 && c <= 0xf4) {
            if (i + 3 >= length || (line[i + 1] & 0xc0) != 0x80 || (line[i + 2] & 0xc0) != 0x80 ||
                (line[i + 3] & 0xc0) != 0x80)
                return 0;
            if (c == 0xf0 && line[i + 1] < 0x90)
                return 0;
            if (c == 0xf4 && line[i + 1] >= 0x90)
                return 0;
            i += 4;
        } else {
            return 0;
        }
        count++;
    }
    *chars += count;
    return 1;
}

static const struct {
    const char *word;
    int length, level;
} SEVERITIES[] = {{"DEBUG", 5, 10}, {"INFO", 4, 20}, {"WARN", 4, 30}, {"ERROR", 5, 40}, {"FATAL", 5, 50}, {"UNSET", 5, 0}};

/* What a line is: 1 a record's first line (its fields set), 0 a line that continues a
 * message, -1 irregular (the Python reader decides). */
static int classify(const unsigned char *line, Py_ssize_t length, int *level, int64_t *stamp, Py_ssize_t *name,
                    Py_ssize_t *name_end, Py_ssize_t *message) {
    if (length == 0 || line[0] != '[')
        return 0; /* cannot start a record (a colour code would be ESC: refused elsewhere) */
    int found = -1;
    for (int s = 0; s < 6; s++) {
        int n = SEVERITIES[s].length;
        if (length >= n + 4 && memcmp(line + 1, SEVERITIES[s].word, n) == 0 && memcmp(line + 1 + n, "] [", 3) == 0) {
            found = s;
            break;
        }
    }
    if (found < 0)
        return 0; /* the Python reader's start pattern needs one of these words, then "] [" */
    Py_ssize_t i = 1 + SEVERITIES[found].length + 3;
    int negative = 0;
    if (i < length && line[i] == '-') {
        negative = 1;
        i++;
    }
    Py_ssize_t digits = i;
    int64_t seconds = 0;
    while (i < length && line[i] >= '0' && line[i] <= '9') {
        if (seconds > MAX_SECONDS)
            return -1; /* the store clamps such a stamp: let Python read it */
        seconds = seconds * 10 + (line[i] - '0');
        i++;
    }
    if (i == digits || seconds > MAX_SECONDS || i + 10 > length || line[i] != '.')
        return -1;
    i++;
    int64_t nanos = 0;
    for (int d = 0; d < 9; d++, i++) {
        if (line[i] < '0' || line[i] > '9')
            return -1;
        nanos = nanos * 10 + (line[i] - '0');
    }
    if (i + 3 > length || memcmp(line + i, "] [", 3) != 0)
        return -1;
    i += 3;
    *name = i;
    for (; i + 3 <= length; i++) {
        if (line[i] == ']' && line[i + 1] == ':' && line[i + 2] == ' ') {
            *name_end = i;
            *message = i + 3;
            *level = SEVERITIES[found].level;
            *stamp = (negative ? -1 : 1) * (seconds * 1000000000LL + nanos);
            return 1;
        }
    }
    return -1;
}

static PyObject *scan(PyObject *self, PyObject *args) {
    Py_buffer view;
    Py_ssize_t start, end, max_records;
    PyObject *nodes, *new_names;
    int want_messages, at_eof;
    if (!PyArg_ParseTuple(args, "y*nnnO!O!pp", &view, &start, &end, &max_records, &PyDict_Type, &nodes, &PyList_Type,
                          &new_names, &want_messages, &at_eof))
        return NULL;
    if (start < 0 || end > view.len || start > end || max_records < 0) {
        PyBuffer_Release(&view);
        PyErr_SetString(PyExc_ValueError, "bad range");
        return NULL;
    }
    const unsigned char *data = view.buf;
    Slot *cache = PyMem_RawCalloc(CACHE_SLOTS, sizeof(Slot));
    if (cache == NULL) {
        PyBuffer_Release(&view);
        return PyErr_NoMemory();
    }
    Buffer stamps = {0}, levels = {0}, ids = {0}, messages = {0}, starts = {0};
    Py_ssize_t count = 0, at = start, record = -1, record_lines = 0, chars = 0;
    Py_ssize_t message_from = 0, record_chars = 0, lines = 0, record_line = 0;
    int status = 1, failed = 0;
    uint32_t first_start = 0;
    if (want_messages && put(&starts, &first_start, 4) < 0)
        failed = 1;
    /* The lines are read without the GIL (the loader's thread beside the app's); it is taken
     * back only to look up a name this call has not met yet. */
    PyThreadState *released = PyEval_SaveThread();
    while (!failed && at < end) {
        const unsigned char *newline = memchr(data + at, '\n', end - at);
        if (newline == NULL) {
            if (at_eof) { /* a last line without its newline: the Python reader says so */
                status = 2;
                break;
            }
            break; /* the rest is not a whole line yet */
        }
        Py_ssize_t length = (const unsigned char *)newline - (data + at);
        int level = 0;
        int64_t stamp = 0;
        Py_ssize_t name = 0, name_end = 0, message = 0;
        int kind = length > MAX_LINE_BYTES ? -1 : classify(data + at, length, &level, &stamp, &name, &name_end, &message);
        Py_ssize_t line_chars = 0;
        if (kind >= 0 && !plain_utf8(data + at, length, &line_chars))
            kind = -1;
        if (kind < 0 || (kind == 0 && record < 0)) {
            status = 2;
            break;
        }
        if (kind == 1) {
            if (record >= 0) { /* the record before this one ends here */
                if (want_messages && end_message(&messages, &starts, data, message_from, at - 1, &chars, record_chars) < 0) {
                    failed = 1;
                    break;
                }
                count++;
                if (count >= max_records) {
                    status = 0;
                    record = -1;
                    break;
                }
            }
            if ((uint64_t)chars > 0xF0000000u) { /* starts are 4 bytes: stop well before */
                status = 0;
                record = -1;
                break;
            }
            const unsigned char *name_bytes = data + at + name;
            Py_ssize_t name_length = name_end - name;
            uint32_t hash = hash_of(name_bytes, name_length), ident = 0;
            Py_ssize_t slot = hash % CACHE_SLOTS;
            int cached = 0;
            for (int probe = 0; probe < 8; probe++, slot = (slot + 1) % CACHE_SLOTS) {
                Slot *entry = &cache[slot];
                if (entry->name == NULL)
                    break;
                if (entry->hash == hash && entry->length == name_length && memcmp(entry->name, name_bytes, name_length) == 0) {
                    ident = entry->ident;
                    cached = 1;
                    break;
                }
            }
            PyObject *key = NULL;
            if (!cached) {
                PyEval_RestoreThread(released);
                key = PyBytes_FromStringAndSize((const char *)name_bytes, name_length);
            }
            PyObject *known = NULL;
            if (cached) {
                /* found */
            } else if (key == NULL) {
                released = PyEval_SaveThread();
                failed = 1;
                break;
            } else if ((known = PyDict_GetItemWithError(nodes, key)) != NULL) {
                ident = (uint32_t)PyLong_AsUnsignedLong(known);
            } else if (PyErr_Occurred()) {
                Py_DECREF(key);
                released = PyEval_SaveThread();
                failed = 1;
                break;
            } else {
                ident = (uint32_t)PyDict_Size(nodes);
                PyObject *number = PyLong_FromUnsignedLong(ident);
                if (number == NULL || PyDict_SetItem(nodes, key, number) < 0 || PyList_Append(new_names, key) < 0) {
                    Py_XDECREF(number);
                    Py_DECREF(key);
                    released = PyEval_SaveThread();
                    failed = 1;
                    break;
                }
                Py_DECREF(number);
            }
            if (!cached) {
                Py_DECREF(key);
                released = PyEval_SaveThread();
                slot = hash % CACHE_SLOTS;
                for (int probe = 0; probe < 8; probe++, slot = (slot + 1) % CACHE_SLOTS) {
                    if (cache[slot].name == NULL) {
                        cache[slot] = (Slot){name_bytes, name_length, hash, ident};
                        break;
                    }
                }
            }
            unsigned char byte = (unsigned char)level;
            if (put(&stamps, &stamp, 8) < 0 || put(&levels, &byte, 1) < 0 || put(&ids, &ident, 4) < 0) {
                failed = 1;
                break;
            }
            record = at;
            record_line = lines;
            record_lines = 1;
            message_from = at + message;
            /* the message's characters: the line's, less those before the message (ASCII
             * up to the name, then the name's own) */
            Py_ssize_t before = 0;
            plain_utf8(data + at, message, &before);
            record_chars = line_chars - before;
        } else {
            if (++record_lines > MAX_RECORD_LINES || at + length - record > MAX_RECORD_BYTES) {
                status = 2;
                break;
            }
            record_chars += 1 + line_chars; /* the newline joining it, and the line */
        }
        at += length + 1;
        lines++;
    }
    PyEval_RestoreThread(released);
    Py_ssize_t stop = at;
    if (!failed && record >= 0) {
        if (status == 1 && at_eof && at >= end) {
            /* the last record ends at the end of the data */
            if (want_messages && end_message(&messages, &starts, data, message_from, end - 1, &chars, record_chars) < 0)
                failed = 1;
            count++;
            stop = end;
        } else {
            /* the record under way is not counted: its fields go */
            stamps.used -= 8;
            levels.used -= 1;
            ids.used -= 4;
            stop = record;
            lines = record_line;
        }
    }
    PyBuffer_Release(&view);
    PyObject *result = NULL;
    if (!failed) {
        if (want_messages && messages.used > 0)
            messages.used -= 1; /* no NUL after the last message */
        result = Py_BuildValue(
            "innny#y#y#", status, stop, count, lines, stamps.data ? stamps.data : "", stamps.used, levels.data ? levels.data : "",
            levels.used, ids.data ? ids.data : "", ids.used);
        if (result != NULL) {
            PyObject *texts = want_messages ? PyBytes_FromStringAndSize(messages.data ? messages.data : "", messages.used)
                                            : Py_NewRef(Py_None);
            PyObject *offsets = want_messages ? PyBytes_FromStringAndSize(starts.data, starts.used) : Py_NewRef(Py_None);
            PyObject *whole = (texts && offsets) ? PyTuple_Pack(9, PyTuple_GET_ITEM(result, 0), PyTuple_GET_ITEM(result, 1),
                                                                 PyTuple_GET_ITEM(result, 2), PyTuple_GET_ITEM(result, 3),
                                                                 PyTuple_GET_ITEM(result, 4), PyTuple_GET_ITEM(result, 5),
                                                                 PyTuple_GET_ITEM(result, 6), texts, offsets)
                                                 : NULL;
            Py_XDECREF(texts);
            Py_XDECREF(offsets);
            Py_DECREF(result);
            result = whole;
        }
    }
    if (result == NULL && !PyErr_Occurred())
        PyErr_NoMemory();
    PyMem_RawFree(cache);
    PyMem_RawFree(stamps.data);
    PyMem_RawFree(levels.data);
    PyMem_RawFree(ids.data);
    PyMem_RawFree(messages.data);
    PyMem_RawFree(starts.data);
    return result;
}

/* Whether data holds needle (lower-case ASCII) when ASCII letters are compared ignoring case. */
static int contains_folded(const unsigned char *data, Py_ssize_t size, const unsigned char *needle, Py_ssize_t length) {
    if (length == 0)
        return 1;
    unsigned char first = needle[0], other = (first >= 'a' && first <= 'z') ? first - 32 : first;
    for (Py_ssize_t i = 0; i + length <= size; i++) {
        unsigned char c = data[i];
        if (c != first && c != other)
            continue;
        Py_ssize_t j = 1;
        for (; j < length; j++) {
            unsigned char x = data[i + j];
            if (x >= 'A' && x <= 'Z')
                x += 32;
            if (x != needle[j])
                break;
        }
        if (j == length)
            return 1;
    }
    return 0;
}

/* contains(data, needle, ignore_case): whether needle is in data (glibc's memmem, several
 * times bytes.find's speed); with ignore_case, needle is lower-case and ASCII letters of data
 * are compared ignoring case (data should be ASCII: the caller checks). */
static PyObject *contains(PyObject *self, PyObject *args) {
    Py_buffer data, needle;
    int ignore_case = 0;
    if (!PyArg_ParseTuple(args, "y*y*|p", &data, &needle, &ignore_case))
        return NULL;
    int found;
    Py_BEGIN_ALLOW_THREADS;
    if (ignore_case)
        found = contains_folded(data.buf, data.len, needle.buf, needle.len);
    else
        found = needle.len == 0 || memmem(data.buf, data.len, needle.buf, needle.len) != NULL;
    Py_END_ALLOW_THREADS;
    PyBuffer_Release(&data);
    PyBuffer_Release(&needle);
    return PyBool_FromLong(found);
}

static PyMethodDef methods[] = {
    {"scan", scan, METH_VARARGS, "Read rcutils default-format records of data[start:end] (see rcutils_scan.c)."},
    {"contains", contains, METH_VARARGS, "Whether needle is in data (memmem; or ignoring ASCII case)."},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef module = {PyModuleDef_HEAD_INIT, "console_tui_rcutils_scan", NULL, -1, methods};

PyMODINIT_FUNC PyInit_console_tui_rcutils_scan(void) { return PyModule_Create(&module); }
