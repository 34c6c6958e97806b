/*
 * tripod-thrust's FMI 2.0 co-simulation binary: every fmi2* function of a CS FMU, over a
 * Python slave class (pythonfmu's Fmi2Slave API) bundled in the FMU's resources/.
 *
 * Why our own: pythonfmu 0.7's binary corrupts the heap at process exit (a C++ static
 * shared_ptr destroyed before an ELF destructor assigns to it; docs/native-layer.md).  This
 * layer owns no C++ statics, registers no exit handler or ELF destructor, and gives Python no
 * pointer into this library, so the host may dlclose it at any time and load it again.
 *
 * Python is never linked: the C API is bound at run time (dlsym), from the host process when
 * it already runs Python (FMPy, libcosimpy), otherwise from the libpython of a Python
 * installation that this library finds and starts itself (a C host: Simulink, Dymola, ...).
 * Only C API functions that exist unchanged in Python 3.11-3.13 are used, with opaque object
 * pointers (no Python headers, no struct layouts but PyStatus), so one binary serves all.
 * An interpreter this library starts is never finalised: numpy cannot be imported twice in one
 * process, and a host may instantiate again after freeing every instance.
 *
 * Threads: every call takes the GIL with PyGILState_Ensure, so any host thread may call.
 * Log messages are copied out under the GIL and handed to the host's logger after releasing
 * it, so a logger that waits on another thread cannot deadlock against Python.
 */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <float.h>
#include <math.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <spawn.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "fmi2Functions.h"

extern char **environ;

/* ------------------------------------------------------------------------------------------ */
/* The Python C API, bound at run time                                                         */

typedef struct PyObj PyObject;                       /* opaque: we never touch a field */
typedef struct { int type; const char *func; const char *err_msg; int exitcode; } PyStatus;
typedef int PyGILState_STATE;
typedef struct PyTS PyThreadState;

#define PY_API(X)                                                                             \
    X(int, Py_IsInitialized, (void))                                                          \
    X(const char *, Py_GetVersion, (void))                                                    \
    X(void, PyPreConfig_InitIsolatedConfig, (void *))                                         \
    X(PyStatus, Py_PreInitialize, (const void *))                                             \
    X(void, PyConfig_InitIsolatedConfig, (void *))                                            \
    X(PyStatus, PyConfig_SetBytesArgv, (void *, ssize_t, char *const *))                      \
    X(PyStatus, Py_InitializeFromConfig, (const void *))                                      \
    X(void, PyConfig_Clear, (void *))                                                         \
    X(PyThreadState *, PyEval_SaveThread, (void))                                             \
    X(PyGILState_STATE, PyGILState_Ensure, (void))                                            \
    X(void, PyGILState_Release, (PyGILState_STATE))                                           \
    X(void, Py_IncRef, (PyObject *))                                                          \
    X(void, Py_DecRef, (PyObject *))                                                          \
    X(PyObject *, PyImport_ImportModule, (const char *))                                      \
    X(PyObject *, PyObject_GetAttrString, (PyObject *, const char *))                         \
    X(PyObject *, PyObject_CallObject, (PyObject *, PyObject *))                              \
    X(PyObject *, PyObject_CallFunction, (PyObject *, const char *, ...))                     \
    X(int, PyObject_IsTrue, (PyObject *))                                                     \
    X(PyObject *, PyFloat_FromDouble, (double))                                               \
    X(double, PyFloat_AsDouble, (PyObject *))                                                 \
    X(PyObject *, PyLong_FromLong, (long))                                                    \
    X(long, PyLong_AsLong, (PyObject *))                                                      \
    X(PyObject *, PyBool_FromLong, (long))                                                    \
    X(PyObject *, PyUnicode_FromString, (const char *))                                       \
    X(PyObject *, PyUnicode_DecodeFSDefault, (const char *))                                  \
    X(const char *, PyUnicode_AsUTF8AndSize, (PyObject *, ssize_t *))                         \
    X(PyObject *, PyList_New, (ssize_t))                                                      \
    X(int, PyList_SetItem, (PyObject *, ssize_t, PyObject *))                                 \
    X(PyObject *, PyList_GetItem, (PyObject *, ssize_t))                                      \
    X(ssize_t, PyList_Size, (PyObject *))                                                     \
    X(int, PyList_Insert, (PyObject *, ssize_t, PyObject *))                                  \
    X(int, PySequence_Contains, (PyObject *, PyObject *))                                     \
    X(PyObject *, PySequence_GetItem, (PyObject *, ssize_t))                                  \
    X(ssize_t, PySequence_Size, (PyObject *))                                                 \
    X(PyObject *, PyBytes_FromStringAndSize, (const char *, ssize_t))                         \
    X(int, PyBytes_AsStringAndSize, (PyObject *, char **, ssize_t *))                         \
    X(PyObject *, PyErr_Occurred, (void))                                                     \
    X(void, PyErr_Fetch, (PyObject **, PyObject **, PyObject **))                             \
    X(void, PyErr_NormalizeException, (PyObject **, PyObject **, PyObject **))                \
    X(void, PyErr_Clear, (void))                                                              \
    X(PyObject *, PySys_GetObject, (const char *))                                            \
    X(int, PySys_SetObject, (const char *, PyObject *))                                       \
    X(PyObject *, PyObject_Str, (PyObject *))

#define PY_DECLARE(ret, name, args) static ret(*name) args;
PY_API(PY_DECLARE)
static PyObject *Py_None_;                  /* &_Py_NoneStruct */
static int (*Py_IsFinalizing_)(void);      /* Py_IsFinalizing (3.13) or _Py_IsFinalizing */

/* Bind every function from `lib` (RTLD_DEFAULT or a libpython handle); NULL, or the name of
   the first symbol missing. */
static const char *bind_python(void *lib)
{
#define PY_BIND(ret, name, args) \
    if (!(*(void **)(&name) = dlsym(lib, #name))) return #name;
    PY_API(PY_BIND)
    if (!(Py_None_ = (PyObject *)dlsym(lib, "_Py_NoneStruct"))) return "_Py_NoneStruct";
    *(void **)(&Py_IsFinalizing_) = dlsym(lib, "Py_IsFinalizing");
    if (!Py_IsFinalizing_) *(void **)(&Py_IsFinalizing_) = dlsym(lib, "_Py_IsFinalizing");
    return NULL;
}

static int python_usable(void)
{
    return Py_IsInitialized && Py_IsInitialized() && !(Py_IsFinalizing_ && Py_IsFinalizing_());
}

static void xdecref(PyObject *o)
{
    if (o) Py_DecRef(o);
}

/* ------------------------------------------------------------------------------------------ */
/* Small C helpers                                                                             */

static char *dupstr(const char *s)
{
    if (!s) s = "";
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (d) memcpy(d, s, n);
    return d;
}

static char *vformat(const char *fmt, va_list ap)
{
    va_list aq;
    va_copy(aq, ap);
    int n = vsnprintf(NULL, 0, fmt, aq);
    va_end(aq);
    if (n < 0) return dupstr(fmt);
    char *s = malloc((size_t)n + 1);
    if (s) vsnprintf(s, (size_t)n + 1, fmt, ap);
    return s;
}

static char *format(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    char *s = vformat(fmt, ap);
    va_end(ap);
    return s;
}

/* file:///a/b%20c, file:/a/b, file://localhost/a/b -> /a/b c (NULL if not a file URI) */
static char *uri_to_path(const char *uri)
{
    const char *p;
    if (!uri) return NULL;
    if (strncmp(uri, "file://localhost/", 17) == 0) p = uri + 16;
    else if (strncmp(uri, "file:///", 8) == 0) p = uri + 7;
    else if (strncmp(uri, "file:/", 6) == 0) p = uri + 5;
    else return NULL;
    char *out = malloc(strlen(p) + 1), *o = out;
    if (!out) return NULL;
    for (; *p; ++p) {
        unsigned v;
        if (p[0] == '%' && p[1] && p[2] && sscanf(p + 1, "%2x", &v) == 1) {
            *o++ = (char)v;
            p += 2;
        } else {
            *o++ = *p;
        }
    }
    *o = '\0';
    size_t n = strlen(out);                        /* no trailing slash */
    while (n > 1 && out[n - 1] == '/') out[--n] = '\0';
    return out;
}

static char *read_first_line(const char *path)
{
    FILE *f = fopen(path, "r");
    if (!f) return NULL;
    char buf[1024];
    char *r = fgets(buf, sizeof buf, f) ? dupstr(buf) : NULL;
    fclose(f);
    if (r) r[strcspn(r, "\r\n")] = '\0';
    return r;
}

/* Run argv, return its stdout+stderr (at most 1 MiB) and exit status. */
/* how long the interpreter may take to answer [s]: $TRIPOD_THRUST_PYTHON_TIMEOUT, else 60 */
static double run_timeout(void)
{
    const char *e = getenv("TRIPOD_THRUST_PYTHON_TIMEOUT");
    double v = e ? atof(e) : 0.0;
    return v > 0.0 && v < 1e6 ? v : 60.0;
}

static char *run_capture(char *const argv[], int *status)
{
    int fd[2];
    *status = -1;
    if (pipe(fd) != 0) return NULL;
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_adddup2(&fa, fd[1], 1);
    posix_spawn_file_actions_adddup2(&fa, fd[1], 2);
    posix_spawn_file_actions_addclose(&fa, fd[0]);
    posix_spawnattr_t at;      /* its own process group: a timeout kills what it started too */
    posix_spawnattr_init(&at);
    posix_spawnattr_setflags(&at, POSIX_SPAWN_SETPGROUP);
    posix_spawnattr_setpgroup(&at, 0);
    pid_t pid;
    int rc = posix_spawnp(&pid, argv[0], &fa, &at, argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    posix_spawnattr_destroy(&at);
    close(fd[1]);
    if (rc != 0) {
        close(fd[0]);
        return NULL;
    }
    size_t cap = 4096, len = 0;
    char *buf = malloc(cap), scratch[4096];
    /* a bounded wait: an interpreter that never answers (a wrong TRIPOD_THRUST_PYTHON) is
       killed after run_timeout() and the instantiation fails with that reason */
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    for (;;) {                 /* read to EOF, so the child never blocks on a full pipe */
        clock_gettime(CLOCK_MONOTONIC, &t1);
        double left = run_timeout() - (double)(t1.tv_sec - t0.tv_sec) -
                      1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
        struct pollfd pfd = {fd[0], POLLIN, 0};
        int pr = left > 0 ? poll(&pfd, 1, (int)(left * 1000.0) + 1) : 0;
        if (pr == 0) {         /* timed out */
            kill(-pid, SIGKILL);
            close(fd[0]);
            while (waitpid(pid, status, 0) < 0 && errno == EINTR) {}
            *status = -2;
            free(buf);
            return NULL;
        }
        if (pr < 0 && errno == EINTR) continue;
        if (buf && cap - len < 2 && cap < (1u << 20)) {
            char *nb = realloc(buf, cap * 2);
            if (nb) buf = nb, cap *= 2;
        }
        int keep = buf && cap - len >= 2;
        ssize_t k = keep ? read(fd[0], buf + len, cap - len - 1) : read(fd[0], scratch, sizeof scratch);
        if (k == 0) break;
        if (k < 0) {
            if (errno == EINTR) continue;
            break;
        }
        if (keep) len += (size_t)k;
    }
    close(fd[0]);
    pid_t w;
    while ((w = waitpid(pid, status, 0)) < 0 && errno == EINTR) {}
    if (w < 0) *status = 0;   /* a host that ignores SIGCHLD: judge by the output alone */
    if (buf) buf[len] = '\0';
    return buf;
}

/* ------------------------------------------------------------------------------------------ */
/* The interpreter: joined or started once per process                                         */

static pthread_mutex_t g_lock = PTHREAD_MUTEX_INITIALIZER;
static int g_ready;          /* the API is bound and an interpreter runs */
static int g_owned;          /* this library started it (a C host) */
static char *g_origin;       /* one line for the log: which Python, and how */
#define STARTED_MARK "_tripod_thrust_fmu_started"   /* in sys when an FMU started Python */

/* The Python interpreter executable to start: $TRIPOD_THRUST_PYTHON, the one the FMU was built
   with (resources/python.txt) if it still exists, else python3 on PATH. */
static char *choose_python(const char *resources)
{
    const char *env = getenv("TRIPOD_THRUST_PYTHON");
    if (env && *env) return dupstr(env);
    char *rec_path = format("%s/python.txt", resources);
    char *rec = rec_path ? read_first_line(rec_path) : NULL;
    free(rec_path);
    if (rec && *rec && access(rec, X_OK) == 0) return rec;
    free(rec);
    return dupstr("python3");
}

/* Start the interpreter of `exe` in this process: ask it (a child process running the bundled
   fmi2bridge.py in `pkgdir`) where its libpython and its sys.path are, load that libpython globally (its
   extension modules resolve symbols from it), initialise isolated (no signal handlers, no
   environment variables), and set sys.path to exactly what `exe` itself has. */
static char *start_python(const char *exe, const char *pkgdir, void **lib_out)
{
    char *bridge = format("%s/fmi2bridge.py", pkgdir);
    char *const argv[] = {(char *)exe, "-I", bridge, "--where", NULL};
    int st;
    char *out = run_capture(argv, &st);
    free(bridge);
    if (!out && st == -2)
        return format("the Python interpreter '%s' did not answer within %g s (set "
                      "TRIPOD_THRUST_PYTHON to a Python 3.11+ with numpy)", exe, run_timeout());
    if (!out) return format("could not run the Python interpreter '%s' (set TRIPOD_THRUST_PYTHON "
                            "to a Python 3.11+ with numpy)", exe);
    if (!WIFEXITED(st) || WEXITSTATUS(st) != 0) {
        char *e = format("the Python interpreter '%s' failed: %.400s", exe, out);
        free(out);
        return e;
    }
    /* line 1: libpython path or "-", line 2: sys.executable, then one sys.path entry a line */
    char *save = NULL, *libpath = strtok_r(out, "\n", &save);
    char *real_exe = strtok_r(NULL, "\n", &save);
    if (!libpath || !real_exe || strcmp(libpath, "-") == 0) {
        char *e = format("the Python at '%s' has no shared libpython (a Python built with "
                         "--enable-shared is needed; Debian: apt-get install libpython3-dev)",
                         real_exe ? real_exe : exe);
        free(out);
        return e;
    }
    void *lib = *lib_out;
    if (!lib) lib = dlopen(libpath, RTLD_NOW | RTLD_GLOBAL);
    if (!lib) {
        char *e = format("could not load %s: %s", libpath, dlerror());
        free(out);
        return e;
    }
    const char *missing = bind_python(lib);
    if (missing) {
        char *e = format("%s lacks %s (Python 3.11 or newer is needed)", libpath, missing);
        free(out);
        return e;
    }
    /* UTF-8 mode: a C host that never called setlocale runs in the "C" locale, whose ASCII
       file-system encoding refuses a resource folder named jurgen with an umlaut.  PyPreConfig
       is public: utf8_mode is its 8th int on POSIX (CPython 3.8-3.13) */
    int pre[32] = {0};
    PyPreConfig_InitIsolatedConfig(pre);
    if (pre[2] == 1 && pre[7] == 0) pre[7] = 1;   /* (isolated = 1 where expected: the layout) */
    PyStatus s = Py_PreInitialize(pre);
    void *config = calloc(1, 1 << 14);   /* a PyConfig, opaque; larger than any version's */
    char *const pyargv[] = {real_exe, NULL};
    if (s.type == 0) {
        PyConfig_InitIsolatedConfig(config);
        s = PyConfig_SetBytesArgv(config, 1, pyargv);   /* program name -> its venv */
    }
    if (s.type == 0) s = Py_InitializeFromConfig(config);
    PyConfig_Clear(config);
    free(config);
    if (s.type != 0) {
        char *e = format("starting Python from %s failed: %s", libpath,
                         s.err_msg ? s.err_msg : "unknown reason");
        free(out);
        return e;
    }
    PyObject *path = PyList_New(0);
    for (char *entry; (entry = strtok_r(NULL, "\n", &save));) {
        PyObject *u = PyUnicode_DecodeFSDefault(entry);
        if (u) {
            PyList_Insert(path, PyList_Size(path), u);
            Py_DecRef(u);
        }
    }
    PySys_SetObject("path", path);
    Py_DecRef(path);
    PySys_SetObject(STARTED_MARK, Py_None_);      /* for a later load of this library */
    const char *ver = Py_GetVersion();   /* "3.11.7 (main, ...": the number only */
    g_origin = format("Python %.*s from %s (%s), started by this FMU", (int)strcspn(ver, " "),
                      ver, real_exe, libpath);
    PyEval_SaveThread();    /* release the GIL: any thread takes it with PyGILState_Ensure */
    free(out);
    *lib_out = lib;
    return NULL;
}

/* Join the process's Python or start one; NULL on success, else the reason (malloc'd). */
static char *ensure_python(const char *resources, const char *pkgdir)
{
    char *err = NULL;
    pthread_mutex_lock(&g_lock);
    if (g_ready && python_usable()) goto done;
    g_ready = 0;
    void *lib = NULL;
    if (dlsym(RTLD_DEFAULT, "Py_IsInitialized")) {
        /* libpython is in the process: a Python host, or a C host linked with it */
        const char *missing = bind_python(RTLD_DEFAULT);
        if (missing) {
            err = format("the process's Python lacks %s (Python 3.11 or newer is needed)", missing);
            goto done;
        }
        if (Py_IsInitialized()) {
            if (!python_usable()) {
                err = dupstr("the host's Python is shutting down");
                goto done;
            }
            /* started by an earlier load of this library (since unloaded), or the host's */
            PyGILState_STATE gil = PyGILState_Ensure();
            g_owned = PySys_GetObject(STARTED_MARK) != NULL;
            PyGILState_Release(gil);
            free(g_origin);
            const char *ver = Py_GetVersion();
            g_origin = format("Python %.*s %s", (int)strcspn(ver, " "), ver,
                              g_owned ? "started by this FMU earlier" : "of the host process");
            g_ready = 1;
            goto done;
        }
        lib = RTLD_DEFAULT;
    }
    char *exe = choose_python(resources);
    free(g_origin);
    g_origin = NULL;
    err = start_python(exe, pkgdir, &lib);
    free(exe);
    if (!err) g_owned = g_ready = 1;
done:
    pthread_mutex_unlock(&g_lock);
    return err;
}

/* ------------------------------------------------------------------------------------------ */
/* An instance                                                                                 */

typedef enum { INSTANTIATED, INIT_MODE, STEP_COMPLETE, STEP_FAILED, TERMINATED, ERRORED } Phase;
static const char *const PHASE_NAMES[] = {"instantiated", "initialization mode", "step complete",
                                          "step failed", "terminated", "error"};

typedef struct {
    int status;
    char *category, *message;
} Msg;

/* the slave's compiled step (slavekit.FastStep; fmu_src/tripod_model/kernel.py: step, or the
   analytic FMU's reduced_model/analytic_kernel.py, compiled): its one argument the addresses of
   its arrays; 1 = outputs written, anything else = failed (a non-finite output, or an exception) */
typedef int32_t (*FastStep)(double **);   /* slavekit.FastStep: step(args) */

typedef struct {
    char *name, *resources, *module, *guid, *bridge_name;
    int visible;
    fmi2CallbackFunctions cb;
    int logging_on, n_categories;
    char **categories;            /* enabled categories; none listed = all */
    Phase phase;
    double last_ok_time;
    int wants_to_terminate;
    /* Python side: the slave, its bound methods, its log queue, the bridge module */
    PyObject *bridge, *m_create, *m_drain, *m_describe, *m_flush, *slave, *log_queue,
        *var_names;
    PyObject *m_setup, *m_enter, *m_exit, *m_step, *m_terminate, *m_get_state, *m_set_state,
        *m_to_bytes, *m_from_bytes, *m_get[4], *m_set[4];
    /* per value reference: type (R I B S) and when it may be set (p fixed parameter,
       t tunable parameter, i input, - never) */
    long n_vars;
    char *var_type, *var_set;
    Msg *pending;                 /* log messages not yet handed to the host */
    int n_pending, cap_pending;
    char **strings;               /* fmi2GetString results, valid until the next call */
    size_t n_strings;
    /* The fast path: a compiled step the slave offers after a step through Python (its
       attribute _fast), run for the next steps (of any size) without entering Python; the
       slave counts them when Python is next entered (_fast_sync). */
    FastStep fast;                /* NULL: every step goes through Python */
    double **fast_args;           /* its argument: the slave's array of its arrays' addresses */
    double *fast_outputs;         /* the outputs it writes (the slave's array) */
    double fast_dt;               /* the step size it last took (first: was offered for) [s] */
    double *fast_dt_slot;         /* where it reads its step size (a new one is written there) */
    double fast_elapsed;          /* the time its steps the slave has not counted yet took [s] */
    long fast_shaft_vr;           /* driving by angle: the shaft angle input's value reference, */
    long fast_omega_vr;           /* omega's (derived from it each step) and the whirl angle's */
    int fast_whirl_at;            /* place among the outputs; fast_shaft_vr -1: by omega */
    int fast_fresh;               /* fast_outputs holds the outputs of the last step */
    int fast_said;                /* the log has said once that the fast path runs */
    long fast_pending;            /* fast steps the slave has not counted yet */
    int *fast_out;                /* per value reference: its place in the outputs, or -1 */
    int *fast_in;                 /* per value reference: 1 + its place among the inputs, or 0 */
    double *fast_in_value;        /* per value reference: that input's value */
    long fast_in_vr[8];           /* the inputs' value references, in the slave's order */
    double *fast_in_slot[8];      /* where the compiled step takes each (NULL: the slave) */
    double fast_in_lo[8], fast_in_hi[8];   /* its allowed range */
    int fast_in_lo_open[8], fast_in_hi_open[8];
    int n_fast_in;
    int fast_in_dirty;            /* inputs set to new values the slave has not seen yet */
    int fast_in_for_slave;        /* ... of which some only the slave can take (no slot) */
} Inst;

typedef struct {
    uint64_t magic;
    PyObject *obj;                /* what the slave's _get_fmu_state returned */
    PyObject *bytes;              /* its serialised form, once asked for */
    Phase phase;
    double last_ok_time;
} State;

#define STATE_MAGIC 0x3153454D41525454ull    /* "TTRAMES1" */
#define SERIAL_HEADER 24                     /* magic, phase, reserved, last_ok_time */
static const char SERIAL_MAGIC[8] = {'T', 'T', 'F', 'M', 'U', 'S', 'T', '1'};

static int category_enabled(const Inst *c, const char *category)
{
    if (!c->logging_on) return 0;
    if (c->n_categories == 0) return 1;
    for (int i = 0; i < c->n_categories; ++i)
        if (strcmp(c->categories[i], category) == 0 || strcmp(c->categories[i], "logAll") == 0)
            return 1;
    return 0;
}

/* Queue a message.  Warnings and errors always reach the host (a user must learn why a call
   failed); other messages only when debug logging is on for their category. */
static void queue_msg(Inst *c, int status, const char *category, char *message /* owned */)
{
    if (!message) return;
    if (status < fmi2Warning && !category_enabled(c, category)) {
        free(message);
        return;
    }
    if (c->n_pending == c->cap_pending) {
        int cap = c->cap_pending ? 2 * c->cap_pending : 8;
        Msg *p = realloc(c->pending, (size_t)cap * sizeof *p);
        if (!p) {
            free(message);
            return;
        }
        c->pending = p;
        c->cap_pending = cap;
    }
    c->pending[c->n_pending++] = (Msg){status, dupstr(category), message};
}

static void logf_(Inst *c, int status, const char *fmt, ...)
{
    static const char *const CATS[] = {"logAll", "logStatusWarning", "logStatusDiscard",
                                       "logStatusError", "logStatusFatal", "logAll"};
    va_list ap;
    va_start(ap, fmt);
    queue_msg(c, status, CATS[status >= 0 && status <= 5 ? status : 0], vformat(fmt, ap));
    va_end(ap);
}

/* Hand queued messages to the host's logger: called with the GIL released.  The FMI logger
   takes a printf format, so '%' is doubled. */
static void flush_logs(Inst *c)
{
    for (int i = 0; i < c->n_pending; ++i) {
        Msg *m = &c->pending[i];
        if (c->cb.logger) {
            size_t n = 0;
            for (const char *p = m->message; *p; ++p) n += (*p == '%') ? 2 : 1;
            char *esc = malloc(n + 1), *o = esc;
            if (esc) {
                for (const char *p = m->message; *p; ++p) {
                    *o++ = *p;
                    if (*p == '%') *o++ = '%';
                }
                *o = '\0';
                c->cb.logger(c->cb.componentEnvironment, c->name, (fmi2Status)m->status,
                             m->category, esc);
                free(esc);
            }
        }
        free(m->category);
        free(m->message);
    }
    c->n_pending = 0;
}

static const char *utf8(PyObject *o)
{
    const char *s = o ? PyUnicode_AsUTF8AndSize(o, NULL) : NULL;
    if (!s) PyErr_Clear();
    return s ? s : "?";
}

/* Move the slave's own log messages (Fmi2Slave.log) into the queue.  With the GIL. */
static void drain_slave_log(Inst *c)
{
    if (!c->log_queue || PyList_Size(c->log_queue) <= 0) return;
    /* the bridge empties the queue and returns [(status, category, message), ...] */
    PyObject *msgs = PyObject_CallFunction(c->m_drain, "(O)", c->log_queue);
    if (!msgs) {
        PyErr_Clear();
        return;
    }
    ssize_t n = PyList_Size(msgs);
    for (ssize_t i = 0; i < n; ++i) {
        PyObject *m = PyList_GetItem(msgs, i);       /* borrowed */
        PyObject *st = PySequence_GetItem(m, 0), *cat = PySequence_GetItem(m, 1),
                 *text = PySequence_GetItem(m, 2);
        long status = st ? PyLong_AsLong(st) : fmi2Error;
        queue_msg(c, (int)status, utf8(cat), dupstr(utf8(text)));
        xdecref(st);
        xdecref(cat);
        xdecref(text);
    }
    PyErr_Clear();
    Py_DecRef(msgs);
}

/* The exception being raised, as text for the log ("Type: message", or a traceback for an
   unexpected error); clears it.  With the GIL. */
static char *take_exception(Inst *c)
{
    PyObject *t = NULL, *v = NULL, *tb = NULL;
    PyErr_Fetch(&t, &v, &tb);
    if (!t) return dupstr("unknown error");
    PyErr_NormalizeException(&t, &v, &tb);
    char *text = NULL;
    PyObject *s = c && c->m_describe
                      ? PyObject_CallFunction(c->m_describe, "(OOO)", t, v ? v : Py_None_,
                                              tb ? tb : Py_None_)
                      : NULL;
    if (!s) {
        PyErr_Clear();
        s = PyObject_Str(v ? v : t);
    }
    text = dupstr(s ? utf8(s) : "unprintable exception");
    if (!s) PyErr_Clear();
    xdecref(s);
    xdecref(t);
    xdecref(v);
    xdecref(tb);
    return text;
}

/* A Python call failed: log why, the instance is in error.  With the GIL. */
static fmi2Status fail(Inst *c, const char *fn)
{
    char *why = take_exception(c);
    logf_(c, fmi2Error, "%s: %s", fn, why);
    free(why);
    c->phase = ERRORED;
    return fmi2Error;
}

/* A state refused (corrupt, foreign, inconsistent): log why; the instance is unchanged, its
   phase included, so the run goes on (or another state is tried).  With the GIL. */
static fmi2Status refuse(Inst *c, const char *fn)
{
    char *why = take_exception(c);
    logf_(c, fmi2Error, "%s: %s", fn, why);
    free(why);
    return fmi2Error;
}

static void release_slave(Inst *c)
{
    PyObject **objs[] = {&c->slave, &c->log_queue, &c->var_names, &c->m_setup, &c->m_enter, &c->m_exit,
                         &c->m_step, &c->m_terminate, &c->m_get_state, &c->m_set_state,
                         &c->m_to_bytes, &c->m_from_bytes, &c->m_get[0], &c->m_get[1],
                         &c->m_get[2], &c->m_get[3], &c->m_set[0], &c->m_set[1],
                         &c->m_set[2], &c->m_set[3]};
    for (size_t i = 0; i < sizeof objs / sizeof *objs; ++i) {
        xdecref(*objs[i]);
        *objs[i] = NULL;
    }
    free(c->var_type);
    free(c->var_set);
    c->var_type = c->var_set = NULL;
    c->n_vars = 0;
    c->fast = NULL;
    c->fast_fresh = 0;
    c->fast_pending = 0;
    c->fast_elapsed = 0.0;
    c->fast_in_dirty = 0;
    c->fast_in_for_slave = 0;
    c->n_fast_in = 0;
    free(c->fast_out);
    free(c->fast_in);
    free(c->fast_in_value);
    c->fast_out = c->fast_in = NULL;
    c->fast_in_value = NULL;
}

/* Create the slave object through the bridge and bind its methods.  With the GIL. */
static int create_slave(Inst *c)
{
    static const char *const GET[4] = {"get_real", "get_integer", "get_boolean", "get_string"};
    static const char *const SET[4] = {"set_real", "set_integer", "set_boolean", "set_string"};
    PyObject *r = PyObject_CallFunction(c->m_create, "(ssssii)", c->module, c->name,
                                        c->resources, c->guid ? c->guid : "", c->visible,
                                        g_owned);
    if (!r) return 0;
    /* (slave, log queue, variable table "Rp" "Ri" "R-" ..., one pair a value reference, and
       the variables' names) */
    c->slave = PySequence_GetItem(r, 0);
    c->log_queue = PySequence_GetItem(r, 1);
    PyObject *table = PySequence_GetItem(r, 2);
    c->var_names = PySequence_GetItem(r, 3);
    Py_DecRef(r);
    if (!c->slave || !c->log_queue || !table || !c->var_names) {
        xdecref(table);
        return 0;
    }
    ssize_t n = 0;
    const char *t = PyUnicode_AsUTF8AndSize(table, &n);
    if (!t) {
        Py_DecRef(table);
        return 0;
    }
    c->n_vars = (long)(n / 2);
    c->var_type = malloc((size_t)c->n_vars + 1);
    c->var_set = malloc((size_t)c->n_vars + 1);
    for (long i = 0; c->var_type && c->var_set && i < c->n_vars; ++i) {
        c->var_type[i] = t[2 * i];
        c->var_set[i] = t[2 * i + 1];
    }
    Py_DecRef(table);
    struct { PyObject **slot; const char *name; } methods[] = {
        {&c->m_setup, "setup_experiment"}, {&c->m_enter, "enter_initialization_mode"},
        {&c->m_exit, "exit_initialization_mode"}, {&c->m_step, "do_step"},
        {&c->m_terminate, "terminate"}, {&c->m_get_state, "_get_fmu_state"},
        {&c->m_set_state, "_set_fmu_state"}, {&c->m_to_bytes, "_fmu_state_to_bytes"},
        {&c->m_from_bytes, "_fmu_state_from_bytes"}, {&c->m_get[0], GET[0]},
        {&c->m_get[1], GET[1]}, {&c->m_get[2], GET[2]}, {&c->m_get[3], GET[3]},
        {&c->m_set[0], SET[0]}, {&c->m_set[1], SET[1]}, {&c->m_set[2], SET[2]},
        {&c->m_set[3], SET[3]}};
    for (size_t i = 0; i < sizeof methods / sizeof *methods; ++i)
        if (!(*methods[i].slot = PyObject_GetAttrString(c->slave, methods[i].name))) return 0;
    return c->var_type && c->var_set;
}

/* ------------------------------------------------------------------------------------------ */
/* Call sequence                                                                               */

enum {
    P_INST = 1 << INSTANTIATED, P_INIT = 1 << INIT_MODE, P_OK = 1 << STEP_COMPLETE,
    P_FAILED = 1 << STEP_FAILED, P_TERM = 1 << TERMINATED, P_ERR = 1 << ERRORED,
    P_ANY = P_INST | P_INIT | P_OK | P_FAILED | P_TERM | P_ERR
};

/* The FMI 2.0 CS state machine: may `fn` be called now?  Logs why not. */
static int allowed(Inst *c, const char *fn, unsigned phases)
{
    if (phases & (1u << c->phase)) return 1;
    logf_(c, fmi2Error, "%s is not allowed in phase '%s'", fn, PHASE_NAMES[c->phase]);
    return 0;
}

static fmi2Status finish(Inst *c, fmi2Status status)
{
    flush_logs(c);
    return status;
}

/* Whether a step of h at time t is the step h0 up to the rounding a master's t_{k+1} - t_k
   carries (FMPy: a few ulps of t): within 64 ulps of max(|t|, h0).  The model applies the same
   rule (reduced_model/scene.py, same_step), so both paths take the same steps. */
static int same_step(double h, double h0, double t)
{
    return fabs(h - h0) <= 64.0 * DBL_EPSILON * fmax(fabs(t), h0);
}

/* Whether x is a value the k-th input of the fast step may take (its range, as the slave's
   check_value: finite, not subnormal, within [lo, hi] or with an open end excluded).  Without
   a slot to write it to, the slave checks it. */
static int fast_in_range(const Inst *c, int k, double x)
{
    if (!c->fast_in_slot[k]) return 1;
    if (!isfinite(x) || fpclassify(x) == FP_SUBNORMAL) return 0;
    if (c->fast_in_lo_open[k] ? x <= c->fast_in_lo[k] : x < c->fast_in_lo[k]) return 0;
    if (c->fast_in_hi_open[k] ? x >= c->fast_in_hi[k] : x > c->fast_in_hi[k]) return 0;
    return 1;
}

/* A new value x of the fast step's input with value reference vr (in its range): where the
   compiled step reads it, and to the slave's variables when Python next sees the instance
   (fast_sync); an input without a slot goes to the slave before the next step. */
static void fast_put(Inst *c, long vr, double x)
{
    int k = c->fast_in[vr] - 1;
    if (c->fast_in_value[vr] == x) return;
    c->fast_in_value[vr] = x;
    c->fast_in_dirty = 1;
    if (c->fast_in_slot[k]) *c->fast_in_slot[k] = x;
    else c->fast_in_for_slave = 1;
}

/* Driving by angle: omega over a step of h such that the whirl angle reaches the master's
   shaft angle at its end, (shaft_angle - whirl_angle) / h: C mirror of slavekit.py's
   omega_by_angle, which the slaves' own steps call (tests/test_fast.py holds them equal bit
   for bit).  0: out of omega's range (the slave's step then refuses it, with the reason). */
static int fast_angle_to_omega(Inst *c, double h)
{
    double w = (c->fast_in_value[c->fast_shaft_vr] - c->fast_outputs[c->fast_whirl_at]) / h;
    if (!fast_in_range(c, c->fast_in[c->fast_omega_vr] - 1, w)) return 0;
    fast_put(c, c->fast_omega_vr, w);
    return 1;
}

/* No fast step until the slave offers one again (inputs set, state restored, reset). */
static void fast_off(Inst *c)
{
    c->fast = NULL;
    c->fast_fresh = 0;
}

/* Before Python sees the instance again: let the slave count the steps the fast path took
   (its time, step counters and output variables), then hand it the inputs set since
   (_fast_inputs: it takes them as a setReal would, and says whether the compiled step goes on
   at them).  The steps come first: they ran at the old inputs.  With the GIL. */
static void fast_sync(Inst *c)
{
    if (!c->slave) return;
    if (c->fast_pending > 0) {
        PyObject *m = PyObject_GetAttrString(c->slave, "_fast_sync");
        PyObject *r = m ? PyObject_CallFunction(m, "(ld)", c->fast_pending, c->fast_elapsed)
                        : NULL;
        c->fast_pending = 0;
        c->fast_elapsed = 0.0;
        if (!r) {
            char *why = take_exception(c);
            logf_(c, fmi2Error, "counting the compiled steps: %s", why);
            free(why);
        }
        xdecref(r);
        xdecref(m);
    }
    if (c->fast_in_dirty) {
        c->fast_in_dirty = 0;
        c->fast_in_for_slave = 0;
        PyObject *v = PyList_New(c->n_fast_in);
        for (int i = 0; v && i < c->n_fast_in; ++i)
            PyList_SetItem(v, i, PyFloat_FromDouble(c->fast_in_value[c->fast_in_vr[i]]));
        PyObject *m = v ? PyObject_GetAttrString(c->slave, "_fast_inputs") : NULL;
        PyObject *r = m ? PyObject_CallFunction(m, "(O)", v) : NULL;
        if (!r) {
            char *why = take_exception(c);
            logf_(c, fmi2Error, "setting the inputs: %s", why);
            free(why);
        }
        if (!r || PyObject_IsTrue(r) <= 0) fast_off(c);   /* the next step goes through Python */
        xdecref(r);
        xdecref(m);
        xdecref(v);
    }
}

/* After a step through Python: take the fast step the slave offers, if any.  The slave's
   _fast is None or a slavekit.FastStep, read here by its field names: step (the function's
   address), args (the address of its argument, the array of its arrays' addresses), outputs
   (the address of the outputs it writes), dt (the step size), dt_slot (where it reads its
   step size: a new one is written there), out_vrs and in_vrs (the value
   references of its outputs and inputs), in_values (the inputs' values) and in_slots (per
   input: the address where the compiled step takes it, lowest, highest value, lowest
   excluded, highest excluded; empty: new inputs go to the slave).  With the GIL. */
static void fast_take(Inst *c)
{
    fast_off(c);
    PyObject *f = PyObject_GetAttrString(c->slave, "_fast");
    if (!f) {
        PyErr_Clear();
        return;
    }
    if (f == Py_None_ || !c->n_vars) {
        Py_DecRef(f);
        return;
    }
    if (!c->fast_out) c->fast_out = malloc((size_t)c->n_vars * sizeof *c->fast_out);
    if (!c->fast_in) c->fast_in = calloc((size_t)c->n_vars, sizeof *c->fast_in);
    if (!c->fast_in_value) c->fast_in_value = calloc((size_t)c->n_vars, sizeof(double));
    static const char *const field[10] = {"step", "dt", "out_vrs", "in_vrs", "in_values",
                                          "args", "in_slots", "outputs", "dt_slot", "by_angle"};
    PyObject *it[10] = {NULL};
    int ok = c->fast_out && c->fast_in && c->fast_in_value;
    for (int i = 0; ok && i < 10; ++i) ok = (it[i] = PyObject_GetAttrString(f, field[i])) != NULL;
    FastStep fn = NULL;
    if (ok) {
        fn = (FastStep)(intptr_t)PyLong_AsLong(it[0]);
        c->fast_dt = PyFloat_AsDouble(it[1]);
        c->fast_dt_slot = (double *)(intptr_t)PyLong_AsLong(it[8]);
        for (long v = 0; v < c->n_vars; ++v) c->fast_out[v] = -1;
        for (ssize_t i = 0; ok && i < PyList_Size(it[2]); ++i) {
            long vr = PyLong_AsLong(PyList_GetItem(it[2], i));
            if (vr >= 0 && vr < c->n_vars) c->fast_out[vr] = (int)i;
        }
        for (long v = 0; v < c->n_vars; ++v) c->fast_in[v] = 0;
        c->n_fast_in = 0;
        for (ssize_t i = 0; ok && i < PyList_Size(it[3]); ++i) {
            long vr = PyLong_AsLong(PyList_GetItem(it[3], i));
            ok = vr >= 0 && vr < c->n_vars && i < 8;
            if (ok) {
                c->fast_in[vr] = (int)i + 1;
                c->fast_in_value[vr] = PyFloat_AsDouble(PyList_GetItem(it[4], i));
                c->fast_in_vr[c->n_fast_in++] = vr;
                c->fast_in_slot[i] = NULL;
                PyObject *t = i < PySequence_Size(it[6]) ? PySequence_GetItem(it[6], i) : NULL;
                if (t) {
                    PyObject *e[5];
                    for (int j = 0; j < 5; ++j) e[j] = PySequence_GetItem(t, j);
                    ok = e[0] && e[1] && e[2] && e[3] && e[4];
                    if (ok) {
                        c->fast_in_slot[i] = (double *)(intptr_t)PyLong_AsLong(e[0]);
                        c->fast_in_lo[i] = PyFloat_AsDouble(e[1]);
                        c->fast_in_hi[i] = PyFloat_AsDouble(e[2]);
                        c->fast_in_lo_open[i] = (int)PyLong_AsLong(e[3]);
                        c->fast_in_hi_open[i] = (int)PyLong_AsLong(e[4]);
                    }
                    for (int j = 0; j < 5; ++j) xdecref(e[j]);
                    Py_DecRef(t);
                }
            }
        }
        c->fast_args = (double **)(intptr_t)PyLong_AsLong(it[5]);
        c->fast_outputs = (double *)(intptr_t)PyLong_AsLong(it[7]);
        /* by_angle: () or (shaft angle's vr, omega's vr, the whirl angle's output place), both
           inputs among the step's, the place among its outputs */
        c->fast_shaft_vr = -1;
        if (ok && PySequence_Size(it[9]) == 3) {
            long a[3];
            for (int j = 0; j < 3; ++j) {
                PyObject *e = PySequence_GetItem(it[9], j);
                a[j] = e ? PyLong_AsLong(e) : -1;
                xdecref(e);
            }
            ok = a[0] >= 0 && a[0] < c->n_vars && c->fast_in[a[0]] &&
                 a[1] >= 0 && a[1] < c->n_vars && c->fast_in[a[1]] &&
                 a[2] >= 0 && a[2] < PyList_Size(it[2]);
            c->fast_shaft_vr = a[0];
            c->fast_omega_vr = a[1];
            c->fast_whirl_at = (int)a[2];
        }
        ok = ok && !PyErr_Occurred() && fn && c->fast_args && c->fast_outputs &&
             c->fast_dt_slot;
    }
    for (int i = 0; i < 10; ++i) xdecref(it[i]);
    Py_DecRef(f);
    if (!ok) {
        PyErr_Clear();
        return;
    }
    c->fast = fn;
    c->fast_fresh = 1;
}

#define GIL_BEGIN PyGILState_STATE gil_ = PyGILState_Ensure(); fast_sync(c);
#define GIL_END        \
    drain_slave_log(c); \
    PyGILState_Release(gil_);

static void destroy(Inst *c)
{
    if (c->bridge && python_usable()) {
        GIL_BEGIN
        if (g_owned && c->m_flush) {     /* no interpreter exit will flush its stdout */
            xdecref(PyObject_CallObject(c->m_flush, NULL));
            PyErr_Clear();
        }
        drain_slave_log(c);
        release_slave(c);
        PyObject *mods[] = {c->bridge, c->m_create, c->m_drain, c->m_describe, c->m_flush};
        for (size_t i = 0; i < sizeof mods / sizeof *mods; ++i) xdecref(mods[i]);
        PyGILState_Release(gil_);
    }
    flush_logs(c);
    free(c->pending);
    for (size_t i = 0; i < c->n_strings; ++i) free(c->strings[i]);
    free(c->strings);
    for (int i = 0; i < c->n_categories; ++i) free(c->categories[i]);
    free(c->categories);
    free(c->var_type);
    free(c->var_set);
    free(c->name);
    free(c->resources);
    free(c->module);
    free(c->guid);
    free(c->bridge_name);
    free(c);
}

/* ------------------------------------------------------------------------------------------ */
/* FMI 2.0: common functions                                                                   */

const char *fmi2GetTypesPlatform(void) { return fmi2TypesPlatform; }
const char *fmi2GetVersion(void) { return fmi2Version; }

fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                              fmi2String fmuResourceLocation,
                              const fmi2CallbackFunctions *functions, fmi2Boolean visible,
                              fmi2Boolean loggingOn)
{
    Inst *c = calloc(1, sizeof *c);
    if (!c) return NULL;
    c->name = dupstr(instanceName);
    c->guid = dupstr(fmuGUID);
    if (functions) c->cb = *functions;
    c->logging_on = loggingOn != fmi2False;
    c->visible = visible != fmi2False;
    char *err = NULL;
    if (fmuType != fmi2CoSimulation) {
        err = dupstr("this FMU supports co-simulation only");
    } else if (!(c->resources = uri_to_path(fmuResourceLocation))) {
        err = format("fmuResourceLocation '%s' is not a file URI",
                     fmuResourceLocation ? fmuResourceLocation : "(null)");
    } else {
        char *f = format("%s/slavemodule.txt", c->resources);
        c->module = f ? read_first_line(f) : NULL;
        free(f);
        if (!c->module || !*c->module)
            err = format("%s/slavemodule.txt is missing: the FMU is incomplete", c->resources);
    }
    /* slavemodule.txt names the slave inside the FMU's own package (PKG.Slave, PKG named after
       the bundled sources' hash: two FMUs, or two builds of one, never share a module); the
       bridge is PKG.fmi2bridge, in resources/PKG/ */
    char *pkgdir = NULL;
    if (!err) {
        const char *dot = strrchr(c->module, '.');
        int n = dot ? (int)(dot - c->module) : 0;
        c->bridge_name = dot ? format("%.*s.fmi2bridge", n, c->module) : dupstr("fmi2bridge");
        pkgdir = dot ? format("%s/%.*s", c->resources, n, c->module) : dupstr(c->resources);
        if (!c->bridge_name || !pkgdir) err = dupstr("out of memory");
    }
    if (!err) err = ensure_python(c->resources, pkgdir);
    free(pkgdir);
    if (err) {
        logf_(c, fmi2Error, "fmi2Instantiate: %s", err);
        free(err);
        destroy(c);
        return NULL;
    }
    int ok = 0;
    GIL_BEGIN
    PyObject *path = PySys_GetObject("path");                 /* borrowed */
    PyObject *res = PyUnicode_DecodeFSDefault(c->resources);
    if (path && res && PySequence_Contains(path, res) == 0) PyList_Insert(path, 0, res);
    xdecref(res);
    c->bridge = PyImport_ImportModule(c->bridge_name);
    if (c->bridge) {
        c->m_create = PyObject_GetAttrString(c->bridge, "create");
        c->m_drain = PyObject_GetAttrString(c->bridge, "drain");
        c->m_describe = PyObject_GetAttrString(c->bridge, "describe");
        c->m_flush = PyObject_GetAttrString(c->bridge, "flush");
    }
    if (c->m_create && c->m_drain && c->m_describe && c->m_flush && create_slave(c)) {
        logf_(c, fmi2OK, "%s", g_origin ? g_origin : "Python");
        ok = 1;
    } else {
        char *why = PyErr_Occurred() ? take_exception(c) : dupstr("incomplete slave");
        logf_(c, fmi2Error, "fmi2Instantiate: %s", why);
        free(why);
    }
    GIL_END
    if (!ok) {
        destroy(c);
        return NULL;
    }
    c->phase = INSTANTIATED;
    flush_logs(c);
    return c;
}

void fmi2FreeInstance(fmi2Component component)
{
    if (component) destroy((Inst *)component);
}

fmi2Status fmi2SetDebugLogging(fmi2Component component, fmi2Boolean loggingOn,
                               size_t nCategories, const fmi2String categories[])
{
    Inst *c = (Inst *)component;
    if (!c) return fmi2Error;
    for (int i = 0; i < c->n_categories; ++i) free(c->categories[i]);
    free(c->categories);
    c->categories = NULL;
    c->n_categories = 0;
    c->logging_on = loggingOn != fmi2False;
    if (nCategories > 0 && categories) {
        c->categories = calloc(nCategories, sizeof *c->categories);
        for (size_t i = 0; c->categories && i < nCategories; ++i)
            c->categories[c->n_categories++] = dupstr(categories[i]);
    }
    return fmi2OK;
}

fmi2Status fmi2SetupExperiment(fmi2Component component, fmi2Boolean toleranceDefined,
                               fmi2Real tolerance, fmi2Real startTime,
                               fmi2Boolean stopTimeDefined, fmi2Real stopTime)
{
    Inst *c = (Inst *)component;
    if (!c) return fmi2Error;
    if (!allowed(c, "fmi2SetupExperiment", P_INST)) return finish(c, fmi2Error);
    fmi2Status st = fmi2OK;
    c->last_ok_time = startTime;
    GIL_BEGIN
    PyObject *stop = stopTimeDefined ? PyFloat_FromDouble(stopTime) : (Py_IncRef(Py_None_), Py_None_);
    PyObject *tol = toleranceDefined ? PyFloat_FromDouble(tolerance) : (Py_IncRef(Py_None_), Py_None_);
    PyObject *r = PyObject_CallFunction(c->m_setup, "(dOO)", startTime, stop, tol);
    xdecref(stop);
    xdecref(tol);
    if (!r) st = fail(c, "fmi2SetupExperiment");
    xdecref(r);
    GIL_END
    return finish(c, st);
}

/* Call a slave method that takes no argument; on success move to `next`. */
static fmi2Status call_and_move(Inst *c, const char *fn, PyObject *method, unsigned phases,
                                Phase next)
{
    if (!c) return fmi2Error;
    if (!allowed(c, fn, phases)) return finish(c, fmi2Error);
    fmi2Status st = fmi2OK;
    fast_off(c);
    GIL_BEGIN
    PyObject *r = PyObject_CallObject(method, NULL);
    if (r) c->phase = next;
    else st = fail(c, fn);
    xdecref(r);
    GIL_END
    return finish(c, st);
}

fmi2Status fmi2EnterInitializationMode(fmi2Component component)
{
    Inst *c = (Inst *)component;
    return call_and_move(c, "fmi2EnterInitializationMode", c ? c->m_enter : NULL, P_INST,
                         INIT_MODE);
}

/* An invalid parameter makes the slave raise here: fmi2Error with the reason logged. */
fmi2Status fmi2ExitInitializationMode(fmi2Component component)
{
    Inst *c = (Inst *)component;
    return call_and_move(c, "fmi2ExitInitializationMode", c ? c->m_exit : NULL, P_INIT,
                         STEP_COMPLETE);
}

fmi2Status fmi2Terminate(fmi2Component component)
{
    Inst *c = (Inst *)component;
    return call_and_move(c, "fmi2Terminate", c ? c->m_terminate : NULL, P_OK | P_FAILED,
                         TERMINATED);
}

/* Back to the state after fmi2Instantiate: a new slave object, every variable at its start. */
fmi2Status fmi2Reset(fmi2Component component)
{
    Inst *c = (Inst *)component;
    if (!c) return fmi2Error;
    fmi2Status st = fmi2OK;
    GIL_BEGIN
    release_slave(c);
    if (create_slave(c)) {
        c->phase = INSTANTIATED;
        c->last_ok_time = 0.0;
        c->wants_to_terminate = 0;
    } else {
        st = fail(c, "fmi2Reset");
    }
    GIL_END
    return finish(c, st);
}

/* ------------------------------------------------------------------------------------------ */
/* Variables                                                                                   */

enum { REAL, INTEGER, BOOLEAN, STRING };
static const char TYPE_CODE[] = "RIBS";
static const char *const TYPE_NAME[] = {"Real", "Integer", "Boolean", "String"};

/* The name of a variable (into buf, for an error message).  With the GIL. */
static const char *var_name(Inst *c, fmi2ValueReference vr, char *buf, size_t size)
{
    PyObject *n = c->var_names ? PySequence_GetItem(c->var_names, (ssize_t)vr) : NULL;
    snprintf(buf, size, "%s", n ? utf8(n) : "?");
    xdecref(n);
    PyErr_Clear();
    return buf;
}

/* The value references as a Python list, each checked for type (and, when setting, for
   whether it may be set now); NULL with the reason logged (no exception set).  With the GIL. */
static PyObject *vr_list(Inst *c, const char *fn, int kind, const fmi2ValueReference vr[],
                         size_t nvr, int setting)
{
    for (size_t i = 0; i < nvr; ++i) {
        if (vr[i] >= (fmi2ValueReference)c->n_vars || c->var_type[vr[i]] != TYPE_CODE[kind]) {
            logf_(c, fmi2Error, "%s: %u is not the value reference of a %s variable", fn,
                  vr[i], TYPE_NAME[kind]);
            return NULL;
        }
        if (!setting) continue;
        char how = c->var_set[vr[i]];
        int ok = (how == 'i' || how == 't') ? (c->phase <= STEP_COMPLETE)
                 : how == 'p'               ? (c->phase <= INIT_MODE)
                                            : 0;
        if (!ok) {
            char name[128];
            logf_(c, fmi2Error, "%s: %s %s be set in phase '%s'", fn,
                  var_name(c, vr[i], name, sizeof name),
                  how == '-' ? "is not an input or parameter: it cannot"
                             : "is a fixed parameter: it cannot",
                  PHASE_NAMES[c->phase]);
            return NULL;
        }
    }
    PyObject *l = PyList_New((ssize_t)nvr);
    for (size_t i = 0; l && i < nvr; ++i) PyList_SetItem(l, (ssize_t)i, PyLong_FromLong((long)vr[i]));
    return l;
}

static void clear_strings(Inst *c)
{
    for (size_t i = 0; i < c->n_strings; ++i) free(c->strings[i]);
    free(c->strings);
    c->strings = NULL;
    c->n_strings = 0;
}

static fmi2Status get_values(Inst *c, int kind, const fmi2ValueReference vr[], size_t nvr,
                             void *out)
{
    static const char *const FN[] = {"fmi2GetReal", "fmi2GetInteger", "fmi2GetBoolean",
                                     "fmi2GetString"};
    if (!c) return fmi2Error;
    /* FMI 2.0 CS: values may be read from initialisation mode on, not right after
       instantiation (the start values are in modelDescription.xml) */
    if (!allowed(c, FN[kind], P_ANY & ~P_INST)) return finish(c, fmi2Error);
    if (nvr == 0) return fmi2OK;
    if (!vr || !out) {
        logf_(c, fmi2Error, "%s: NULL array", FN[kind]);
        return finish(c, fmi2Error);
    }
    if (kind == REAL && c->fast_fresh) {      /* outputs of the last step, without Python */
        size_t i = 0;
        while (i < nvr && vr[i] < (fmi2ValueReference)c->n_vars && c->fast_out[vr[i]] >= 0) ++i;
        if (i == nvr) {
            for (i = 0; i < nvr; ++i) ((fmi2Real *)out)[i] = c->fast_outputs[c->fast_out[vr[i]]];
            return fmi2OK;
        }
    }
    fmi2Status st = fmi2OK;
    GIL_BEGIN
    PyObject *l = vr_list(c, FN[kind], kind, vr, nvr, 0);
    PyObject *r = l ? PyObject_CallFunction(c->m_get[kind], "(O)", l) : NULL;
    xdecref(l);
    if (!l) {
        st = fmi2Error;
    } else if (!r) {
        st = fail(c, FN[kind]);
    } else {
        if (kind == STRING) {
            clear_strings(c);
            c->strings = calloc(nvr, sizeof *c->strings);
        }
        for (size_t i = 0; i < nvr; ++i) {
            PyObject *x = PySequence_GetItem(r, (ssize_t)i);
            if (!x) break;
            switch (kind) {
            case REAL: ((fmi2Real *)out)[i] = PyFloat_AsDouble(x); break;
            case INTEGER: ((fmi2Integer *)out)[i] = (fmi2Integer)PyLong_AsLong(x); break;
            case BOOLEAN: ((fmi2Boolean *)out)[i] = PyObject_IsTrue(x) > 0; break;
            default:
                if (c->strings) {
                    c->strings[c->n_strings++] = dupstr(utf8(x));
                    ((fmi2String *)out)[i] = c->strings[i];
                }
            }
            Py_DecRef(x);
        }
        if (PyErr_Occurred()) st = fail(c, FN[kind]);
    }
    xdecref(r);
    GIL_END
    return finish(c, st);
}

static fmi2Status set_values(Inst *c, int kind, const fmi2ValueReference vr[], size_t nvr,
                             const void *values)
{
    static const char *const FN[] = {"fmi2SetReal", "fmi2SetInteger", "fmi2SetBoolean",
                                     "fmi2SetString"};
    if (!c) return fmi2Error;
    if (!allowed(c, FN[kind], P_INST | P_INIT | P_OK)) return finish(c, fmi2Error);
    if (nvr == 0) return fmi2OK;
    if (!vr || !values) {
        logf_(c, fmi2Error, "%s: NULL array", FN[kind]);
        return finish(c, fmi2Error);
    }
    if (kind == REAL && c->fast && c->phase == STEP_COMPLETE) {
        /* a master that sets inputs each step (a driveline co-simulation): no Python here.
           A new value in range goes where the compiled step reads it (its slot; the step
           derives its operating point), and to the slave's variables when Python next sees
           the instance (fast_sync); an input without a slot goes to the slave before the next
           step, which runs compiled if the slave takes it. */
        size_t i = 0;
        int valid = 1;
        for (; i < nvr && vr[i] < (fmi2ValueReference)c->n_vars && c->fast_in[vr[i]]; ++i)
            valid = valid && fast_in_range(c, c->fast_in[vr[i]] - 1,
                                           ((const fmi2Real *)values)[i]);
        if (i == nvr && valid) {       /* else Python takes them and a step refuses them */
            for (i = 0; i < nvr; ++i) fast_put(c, (long)vr[i], ((const fmi2Real *)values)[i]);
            return fmi2OK;
        }
    }
    fast_off(c);
    fmi2Status st = fmi2OK;
    GIL_BEGIN
    PyObject *l = vr_list(c, FN[kind], kind, vr, nvr, 1);
    PyObject *v = l ? PyList_New((ssize_t)nvr) : NULL;
    for (size_t i = 0; v && i < nvr; ++i) {
        PyObject *x;
        switch (kind) {
        case REAL: x = PyFloat_FromDouble(((const fmi2Real *)values)[i]); break;
        case INTEGER: x = PyLong_FromLong(((const fmi2Integer *)values)[i]); break;
        case BOOLEAN: x = PyBool_FromLong(((const fmi2Boolean *)values)[i] != fmi2False); break;
        default: {
            fmi2String s = ((const fmi2String *)values)[i];
            x = PyUnicode_FromString(s ? s : "");
        }
        }
        PyList_SetItem(v, (ssize_t)i, x);
    }
    if (!l) {
        st = fmi2Error;
    } else {
        PyObject *r = v ? PyObject_CallFunction(c->m_set[kind], "(OO)", l, v) : NULL;
        if (!r) st = fail(c, FN[kind]);
        xdecref(r);
    }
    xdecref(l);
    xdecref(v);
    GIL_END
    return finish(c, st);
}

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Real value[])
{
    return get_values((Inst *)c, REAL, vr, nvr, value);
}
fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Integer value[])
{
    return get_values((Inst *)c, INTEGER, vr, nvr, value);
}
fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Boolean value[])
{
    return get_values((Inst *)c, BOOLEAN, vr, nvr, value);
}
fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2String value[])
{
    return get_values((Inst *)c, STRING, vr, nvr, (void *)value);
}
fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Real value[])
{
    return set_values((Inst *)c, REAL, vr, nvr, value);
}
fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Integer value[])
{
    return set_values((Inst *)c, INTEGER, vr, nvr, value);
}
fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Boolean value[])
{
    return set_values((Inst *)c, BOOLEAN, vr, nvr, value);
}
fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2String value[])
{
    return set_values((Inst *)c, STRING, vr, nvr, (const void *)value);
}

/* ------------------------------------------------------------------------------------------ */
/* FMU state                                                                                   */

static State *as_state(Inst *c, const char *fn, fmi2FMUstate s)
{
    State *st = (State *)s;
    if (st && st->magic == STATE_MAGIC) return st;
    logf_(c, fmi2Error, "%s: not an FMU state of this FMU", fn);
    return NULL;
}

fmi2Status fmi2GetFMUstate(fmi2Component component, fmi2FMUstate *FMUstate)
{
    Inst *c = (Inst *)component;
    if (!c || !FMUstate) return fmi2Error;
    State *s = *FMUstate ? as_state(c, "fmi2GetFMUstate", *FMUstate) : calloc(1, sizeof *s);
    if (!s) return finish(c, fmi2Error);
    fmi2Status st = fmi2OK;
    GIL_BEGIN
    PyObject *obj = PyObject_CallObject(c->m_get_state, NULL);
    if (obj) {                            /* a state given back is overwritten in place */
        xdecref(s->obj);
        xdecref(s->bytes);
        *s = (State){STATE_MAGIC, obj, NULL, c->phase, c->last_ok_time};
        *FMUstate = s;
    } else {
        if (!*FMUstate) free(s);
        st = fail(c, "fmi2GetFMUstate");
    }
    GIL_END
    return finish(c, st);
}

/* Restores the slave and the call sequence's phase (a rollback out of an error, too). */
fmi2Status fmi2SetFMUstate(fmi2Component component, fmi2FMUstate FMUstate)
{
    Inst *c = (Inst *)component;
    if (!c) return fmi2Error;
    State *s = as_state(c, "fmi2SetFMUstate", FMUstate);
    if (!s) return finish(c, fmi2Error);
    fmi2Status st = fmi2OK;
    fast_off(c);
    GIL_BEGIN
    PyObject *r = PyObject_CallFunction(c->m_set_state, "(O)", s->obj);
    if (r) {
        c->phase = s->phase;
        c->last_ok_time = s->last_ok_time;
        c->wants_to_terminate = 0;
        fast_take(c);                 /* the slave may offer the compiled step at once */
    } else {
        st = refuse(c, "fmi2SetFMUstate");
    }
    xdecref(r);
    GIL_END
    return finish(c, st);
}

fmi2Status fmi2FreeFMUstate(fmi2Component component, fmi2FMUstate *FMUstate)
{
    Inst *c = (Inst *)component;
    if (!c || !FMUstate) return fmi2Error;
    if (!*FMUstate) return fmi2OK;
    State *s = as_state(c, "fmi2FreeFMUstate", *FMUstate);
    if (!s) return finish(c, fmi2Error);
    if (python_usable()) {
        GIL_BEGIN
        xdecref(s->obj);
        xdecref(s->bytes);
        GIL_END
    }
    /* volatile: a plain store before free() is dead to the optimiser, and the magic is what
       refuses a freed state handed back (as long as the allocator leaves the word alone) */
    *(volatile __typeof__(s->magic) *)&s->magic = 0;
    free(s);
    *FMUstate = NULL;
    return finish(c, fmi2OK);
}

/* The serialised state: a 24-byte header (magic, phase, last successful time) and the
   slave's _fmu_state_to_bytes.  Computed once per state and kept for fmi2SerializeFMUstate. */
static int serialise(Inst *c, State *s, const char *fn)
{
    if (s->bytes) return 1;
    s->bytes = PyObject_CallFunction(c->m_to_bytes, "(O)", s->obj);
    if (!s->bytes) fail(c, fn);
    return s->bytes != NULL;
}

fmi2Status fmi2SerializedFMUstateSize(fmi2Component component, fmi2FMUstate FMUstate, size_t *size)
{
    Inst *c = (Inst *)component;
    if (!c || !size) return fmi2Error;
    State *s = as_state(c, "fmi2SerializedFMUstateSize", FMUstate);
    if (!s) return finish(c, fmi2Error);
    fmi2Status st = fmi2Error;
    GIL_BEGIN
    char *buf;
    ssize_t n;
    if (serialise(c, s, "fmi2SerializedFMUstateSize") &&
        PyBytes_AsStringAndSize(s->bytes, &buf, &n) == 0) {
        *size = SERIAL_HEADER + (size_t)n;
        st = fmi2OK;
    }
    PyErr_Clear();
    GIL_END
    return finish(c, st);
}

fmi2Status fmi2SerializeFMUstate(fmi2Component component, fmi2FMUstate FMUstate,
                                 fmi2Byte serializedState[], size_t size)
{
    Inst *c = (Inst *)component;
    if (!c || !serializedState) return fmi2Error;
    State *s = as_state(c, "fmi2SerializeFMUstate", FMUstate);
    if (!s) return finish(c, fmi2Error);
    fmi2Status st = fmi2Error;
    GIL_BEGIN
    char *buf;
    ssize_t n;
    if (serialise(c, s, "fmi2SerializeFMUstate") &&
        PyBytes_AsStringAndSize(s->bytes, &buf, &n) == 0) {
        if (size < SERIAL_HEADER + (size_t)n) {
            logf_(c, fmi2Error, "fmi2SerializeFMUstate: %zu bytes given, %zu needed", size,
                  SERIAL_HEADER + (size_t)n);
        } else {
            int32_t head[2] = {(int32_t)s->phase, 0};
            memcpy(serializedState, SERIAL_MAGIC, 8);
            memcpy(serializedState + 8, head, 8);
            memcpy(serializedState + 16, &s->last_ok_time, 8);
            memcpy(serializedState + SERIAL_HEADER, buf, (size_t)n);
            st = fmi2OK;
        }
    }
    PyErr_Clear();
    GIL_END
    return finish(c, st);
}

fmi2Status fmi2DeSerializeFMUstate(fmi2Component component, const fmi2Byte serializedState[],
                                   size_t size, fmi2FMUstate *FMUstate)
{
    Inst *c = (Inst *)component;
    if (!c || !FMUstate) return fmi2Error;
    int32_t head[2];
    if (!serializedState || size < SERIAL_HEADER || memcmp(serializedState, SERIAL_MAGIC, 8)) {
        logf_(c, fmi2Error, "fmi2DeSerializeFMUstate: not a serialised state of this FMU");
        return finish(c, fmi2Error);
    }
    memcpy(head, serializedState + 8, 8);
    double t_ok;
    memcpy(&t_ok, serializedState + 16, 8);
    if (head[0] < INSTANTIATED || head[0] > ERRORED || !isfinite(t_ok)) {
        logf_(c, fmi2Error, "fmi2DeSerializeFMUstate: corrupt header");
        return finish(c, fmi2Error);
    }
    State *s = calloc(1, sizeof *s);
    if (!s) return fmi2Error;
    fmi2Status st = fmi2OK;
    GIL_BEGIN
    PyObject *b = PyBytes_FromStringAndSize(serializedState + SERIAL_HEADER,
                                            (ssize_t)(size - SERIAL_HEADER));
    PyObject *obj = b ? PyObject_CallFunction(c->m_from_bytes, "(O)", b) : NULL;
    xdecref(b);
    if (obj) {
        *s = (State){STATE_MAGIC, obj, NULL, (Phase)head[0], t_ok};
        *FMUstate = s;
    } else {
        free(s);
        st = refuse(c, "fmi2DeSerializeFMUstate");
    }
    GIL_END
    return finish(c, st);
}

/* ------------------------------------------------------------------------------------------ */
/* Co-simulation                                                                               */

/* The model refusing a step (do_step returns False: an invalid input, a non-finite result) is
   fmi2Discard: the outputs keep the last good step and the slave asks to terminate. */
fmi2Status fmi2DoStep(fmi2Component component, fmi2Real currentCommunicationPoint,
                      fmi2Real communicationStepSize, fmi2Boolean noSetFMUStatePriorToCurrentPoint)
{
    (void)noSetFMUStatePriorToCurrentPoint;
    Inst *c = (Inst *)component;
    if (!c) return fmi2Error;
    if (!allowed(c, "fmi2DoStep", P_OK)) return finish(c, fmi2Error);
    if (!(communicationStepSize > 0.0) || !isfinite(communicationStepSize) ||
        !isfinite(currentCommunicationPoint)) {
        logf_(c, fmi2Error, "fmi2DoStep: communicationStepSize = %g at t = %g: must be finite "
              "and > 0", communicationStepSize, currentCommunicationPoint);
        return finish(c, fmi2Error);
    }
    fmi2Status st = fmi2OK;
    if (c->fast && c->fast_shaft_vr >= 0 && !fast_angle_to_omega(c, communicationStepSize))
        fast_off(c);                  /* omega out of range: the slave's step refuses it */
    if (c->fast && c->fast_in_for_slave) {
        GIL_BEGIN                     /* new inputs: the slave takes them (or turns us off) */
        GIL_END
    }
    if (c->fast) {
        /* a new step size: the step derives its operating point at it, as the model's own
           step does (a step within the rounding of the last one is that one: same_step) */
        if (!same_step(communicationStepSize, c->fast_dt, currentCommunicationPoint))
            *c->fast_dt_slot = c->fast_dt = communicationStepSize;
        int32_t ok = c->fast(c->fast_args);
        c->fast_pending++;            /* the state has moved, whatever the outcome */
        c->fast_elapsed += c->fast_dt;
        if (ok == 1) {
            c->fast_fresh = 1;
            c->last_ok_time = currentCommunicationPoint + communicationStepSize;
            if (c->fast_said) return fmi2OK;
            c->fast_said = 1;
            logf_(c, fmi2OK, "fmi2DoStep: from t = %g s, steps run "
                  "compiled, without entering Python", currentCommunicationPoint);
            return finish(c, fmi2OK);
        }
        fast_off(c);                  /* the slave says why, as for a step through Python */
        GIL_BEGIN
        PyObject *m = PyObject_GetAttrString(c->slave, "_fast_failed");
        PyObject *r = m ? PyObject_CallFunction(m, "(di)", currentCommunicationPoint, (int)ok)
                        : NULL;
        if (!r) PyErr_Clear();
        xdecref(r);
        xdecref(m);
        c->phase = STEP_FAILED;
        c->last_ok_time = currentCommunicationPoint;
        c->wants_to_terminate = 1;
        GIL_END
        return finish(c, fmi2Discard);
    }
    fast_off(c);
    GIL_BEGIN
    PyObject *r = PyObject_CallFunction(c->m_step, "(dd)", currentCommunicationPoint,
                                        communicationStepSize);
    if (!r) {
        st = fail(c, "fmi2DoStep");
    } else if (PyObject_IsTrue(r) > 0) {
        c->last_ok_time = currentCommunicationPoint + communicationStepSize;
        fast_take(c);
    } else {
        c->phase = STEP_FAILED;
        c->last_ok_time = currentCommunicationPoint;
        c->wants_to_terminate = 1;
        st = fmi2Discard;
    }
    xdecref(r);
    GIL_END
    return finish(c, st);
}

fmi2Status fmi2CancelStep(fmi2Component component)
{
    Inst *c = (Inst *)component;
    if (!c) return fmi2Error;
    logf_(c, fmi2Error, "fmi2CancelStep: no step is pending (this FMU steps synchronously)");
    return finish(c, fmi2Error);
}

static fmi2Status unsupported(fmi2Component component, const char *what)
{
    Inst *c = (Inst *)component;
    if (!c) return fmi2Error;
    logf_(c, fmi2Error, "%s", what);
    return finish(c, fmi2Error);
}

fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference vUnknown_ref[],
                                        size_t nUnknown, const fmi2ValueReference vKnown_ref[],
                                        size_t nKnown, const fmi2Real dvKnown[], fmi2Real dvUnknown[])
{
    (void)vUnknown_ref, (void)nUnknown, (void)vKnown_ref, (void)nKnown, (void)dvKnown, (void)dvUnknown;
    return unsupported(c, "fmi2GetDirectionalDerivative: not provided "
                          "(providesDirectionalDerivative = false)");
}

fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                       const fmi2Integer order[], const fmi2Real value[])
{
    (void)vr, (void)nvr, (void)order, (void)value;
    return unsupported(c, "fmi2SetRealInputDerivatives: not supported (canInterpolateInputs = false)");
}

fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                        const fmi2Integer order[], fmi2Real value[])
{
    (void)vr, (void)nvr, (void)order, (void)value;
    return unsupported(c, "fmi2GetRealOutputDerivatives: not provided (maxOutputDerivativeOrder = 0)");
}

/* Status inquiries: only the two a synchronous FMU can answer; the rest are fmi2Discard
   ("not available"), as the standard asks. */
fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind s, fmi2Status *value)
{
    (void)c, (void)s, (void)value;
    return fmi2Discard;
}

fmi2Status fmi2GetRealStatus(fmi2Component component, const fmi2StatusKind s, fmi2Real *value)
{
    Inst *c = (Inst *)component;
    if (!c || !value || s != fmi2LastSuccessfulTime) return fmi2Discard;
    *value = c->last_ok_time;
    return fmi2OK;
}

fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind s, fmi2Integer *value)
{
    (void)c, (void)s, (void)value;
    return fmi2Discard;
}

fmi2Status fmi2GetBooleanStatus(fmi2Component component, const fmi2StatusKind s, fmi2Boolean *value)
{
    Inst *c = (Inst *)component;
    if (!c || !value || s != fmi2Terminated) return fmi2Discard;
    *value = c->wants_to_terminate ? fmi2True : fmi2False;
    return fmi2OK;
}

fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind s, fmi2String *value)
{
    (void)c, (void)s, (void)value;
    return fmi2Discard;
}
