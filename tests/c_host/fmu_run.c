/* A plain FMI 2.0 co-simulation host, one source for Linux (dlopen) and Windows (LoadLibraryW;
   cross-compiled with mingw-w64 and run under wine64 by tests/test_native_fmu.py), as a
   driveline tool loads an FMU that needs nothing else.  Runs STEPS steps of DT, a master moving
   every input every step (input k at (k + 1) 100 sin((k + 1) 7 t), or given as
   VR:OFFSET:AMPLITUDE:RATE, OFFSET + AMPLITUDE sin(RATE t)), and writes every output
   after every step to OUT (doubles); takes the FMU state halfway, serialises and deserialises
   it, runs the second half again from it, and checks the outputs bit for bit.  Then prints
   whether a Python library is in the process, and two times: from the start of the program
   (before the binary is loaded) to the first step done, and the mean of the steps after it.

   usage: fmu_run BINARY GUID STEPS DT OUT IN_VRS OUT_VRS [INTS]   (VRS: comma-separated;
   INTS: VR=VALUE,... Integer parameters set before initialisation)
   With FMU_RUN_STATE_OUT=FILE in the environment the serialised state taken halfway is written
   there; with FMU_RUN_STATE_IN=FILE the run is a resumed one, as fmusim restores a state: the
   state read from FILE is set right after fmi2Instantiate (no start value, no initialisation)
   and the second half stepped from it (the first half's rows are zeros). */
#ifndef _WIN32
#define _POSIX_C_SOURCE 200809L   /* clock_gettime under -std=c99 */
#endif
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi2FunctionTypes.h"   /* the types only: the functions are looked up */

#ifdef _WIN32
#include <windows.h>
#include <psapi.h>
#include <shellapi.h>
static void *open_library(void)
{
    int n = 0;    /* the path as Windows hands it, UTF-16: the command line's first argument */
    wchar_t **wargv = CommandLineToArgvW(GetCommandLineW(), &n);
    void *lib = (wargv && n > 1) ? (void *)LoadLibraryW(wargv[1]) : NULL;
    LocalFree(wargv);
    return lib;
}
static void *sym(void *lib, const char *name) { return (void *)GetProcAddress((HMODULE)lib, name); }
static int python_loaded(void)
{
    HMODULE mods[1024];
    DWORD need = 0;
    if (!EnumProcessModules(GetCurrentProcess(), mods, sizeof mods, &need)) return -1;
    for (DWORD i = 0; i < need / sizeof(HMODULE) && i < 1024; ++i) {
        char name[MAX_PATH];
        if (GetModuleFileNameA(mods[i], name, MAX_PATH) && strstr(_strlwr(name), "python"))
            return 1;
    }
    return 0;
}
#else
#include <dlfcn.h>
static char *g_path;
static void *open_library(void) { return dlopen(g_path, RTLD_NOW | RTLD_LOCAL); }
static void *sym(void *lib, const char *name) { return dlsym(lib, name); }
static int python_loaded(void)
{
    FILE *f = fopen("/proc/self/maps", "r");
    if (!f) return -1;
    char line[4096];
    int found = 0;
    while (fgets(line, sizeof line, f)) found |= strstr(line, "libpython") != NULL;
    fclose(f);
    return found;
}
#endif

#ifdef _WIN32
static double now(void)
{
    LARGE_INTEGER f, c;
    QueryPerformanceFrequency(&f);
    QueryPerformanceCounter(&c);
    return (double)c.QuadPart / (double)f.QuadPart;
}
#else
#include <time.h>
static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}
#endif

static int g_failures;
static double g_first_done, g_steps_time;

static void logger(fmi2ComponentEnvironment env, fmi2String name, fmi2Status status,
                   fmi2String category, fmi2String message, ...)
{
    (void)env;
    va_list ap;
    va_start(ap, message);
    fprintf(stderr, "[%s|%d|%s] ", name, (int)status, category ? category : "");
    vfprintf(stderr, message, ap);
    fputc('\n', stderr);
    va_end(ap);
}

static void check(const char *name, int ok)
{
    printf("check %s %s\n", name, ok ? "ok" : "FAILED");
    if (!ok) g_failures++;
}

static int parse_vrs(const char *s, fmi2ValueReference *vr, int max)
{
    int n = 0;
    while (*s && n < max) {
        vr[n++] = (fmi2ValueReference)strtoul(s, (char **)&s, 10);
        if (*s == ',') s++;
    }
    return n;
}

#define F(name) static name##TYPE *name;
F(fmi2Instantiate) F(fmi2FreeInstance) F(fmi2SetupExperiment) F(fmi2EnterInitializationMode)
F(fmi2ExitInitializationMode) F(fmi2Terminate) F(fmi2DoStep) F(fmi2GetReal) F(fmi2SetReal)
F(fmi2GetFMUstate) F(fmi2SetFMUstate) F(fmi2FreeFMUstate) F(fmi2SerializedFMUstateSize)
F(fmi2SerializeFMUstate) F(fmi2DeSerializeFMUstate) F(fmi2SetInteger)
#undef F

static fmi2ValueReference g_in[32], g_out[64];
static double g_offset[32], g_amp[32], g_rate[32];
static int g_nin, g_nout;

/* the inputs "VR[:OFFSET:AMPLITUDE:RATE],...": each one's signal */
static int parse_inputs(const char *s)
{
    int n = 0;
    while (s && *s && n < 32) {
        char *end;
        g_in[n] = (fmi2ValueReference)strtoul(s, &end, 10);
        g_offset[n] = 0.0;
        g_amp[n] = (n + 1) * 100.0;
        g_rate[n] = (n + 1) * 7.0;
        if (*end == ':') {
            g_offset[n] = strtod(end + 1, &end);
            if (*end == ':') g_amp[n] = strtod(end + 1, &end);
            if (*end == ':') g_rate[n] = strtod(end + 1, &end);
        }
        ++n;
        s = *end == ',' ? end + 1 : NULL;
    }
    return n;
}

/* steps k0 .. k1 - 1 of dt, the outputs after each into rows */
static int run(fmi2Component c, int k0, int k1, double dt, double *rows)
{
    for (int k = k0; k < k1; ++k) {
        double t = k * dt, u[32];
        for (int i = 0; i < g_nin; ++i) u[i] = g_offset[i] + g_amp[i] * sin(g_rate[i] * t);
        if (fmi2SetReal(c, g_in, (size_t)g_nin, u) != fmi2OK) return 0;
        if (fmi2DoStep(c, t, dt, fmi2True) != fmi2OK) return 0;
        if (fmi2GetReal(c, g_out, (size_t)g_nout, rows + (size_t)k * g_nout) != fmi2OK) return 0;
        if (k == 0) g_first_done = now();
    }
    return 1;
}

/* terminate and free the instance, then every row into path */
static void finish(fmi2Component c, const char *path, const double *rows, int steps)
{
    check("terminate", fmi2Terminate(c) == fmi2OK);
    fmi2FreeInstance(c);
    FILE *f = fopen(path, "wb");
    check("write", f && fwrite(rows, sizeof *rows, (size_t)steps * g_nout, f) ==
                             (size_t)steps * g_nout);
    if (f) fclose(f);
}

int main(int argc, char **argv)
{
    double t_start = now();
    if (argc != 8 && argc != 9) {
        fprintf(stderr, "usage: fmu_run BINARY GUID STEPS DT OUT IN_VRS OUT_VRS [INTS]\n");
        return 2;
    }
#ifndef _WIN32
    g_path = argv[1];
#endif
    void *lib = open_library();
    if (!lib) {
        fprintf(stderr, "fmu_run: cannot load the binary\n");
        return 2;
    }
#define F(name) name = (name##TYPE *)sym(lib, #name); if (!name) { fprintf(stderr, "no %s\n", #name); return 2; }
    F(fmi2Instantiate) F(fmi2FreeInstance) F(fmi2SetupExperiment) F(fmi2EnterInitializationMode)
    F(fmi2ExitInitializationMode) F(fmi2Terminate) F(fmi2DoStep) F(fmi2GetReal) F(fmi2SetReal)
    F(fmi2GetFMUstate) F(fmi2SetFMUstate) F(fmi2FreeFMUstate) F(fmi2SerializedFMUstateSize)
    F(fmi2SerializeFMUstate) F(fmi2DeSerializeFMUstate) F(fmi2SetInteger)
#undef F
    int steps = atoi(argv[3]);
    double dt = atof(argv[4]);
    g_nin = parse_inputs(argv[6]);
    g_nout = parse_vrs(argv[7], g_out, 64);
    if (steps < 2 || !(dt > 0)) return 2;
    double *rows = calloc((size_t)steps * g_nout, sizeof *rows);
    double *again = calloc((size_t)steps * g_nout, sizeof *again);
    fmi2CallbackFunctions cb = {logger, calloc, free, NULL, NULL};
    /* the FMU's resources/ beside binaries/ (an FMU whose binary reads them needs the URI) */
    char uri[4096] = "file:///nowhere";
    const char *bin = strstr(argv[1], "binaries");
    if (bin && bin - argv[1] < 4000)
        snprintf(uri, sizeof uri, "file://%.*sresources", (int)(bin - argv[1]), argv[1]);
    fmi2Component c = fmi2Instantiate("a", fmi2CoSimulation, argv[2], uri, &cb,
                                      fmi2False, fmi2False);
    check("instantiate", c != NULL);
    if (!c || !rows || !again) return 1;
    int half = steps / 2;
    const char *state_in = getenv("FMU_RUN_STATE_IN");
    if (state_in && *state_in) {    /* the resumed run */
        FILE *f = fopen(state_in, "rb");
        static fmi2Byte blob[1 << 24];
        size_t size = f ? fread(blob, 1, sizeof blob, f) : 0;
        if (f) fclose(f);
        fmi2FMUstate st = NULL;
        check("read state", size > 0 && size < sizeof blob);
        check("deserialise", fmi2DeSerializeFMUstate(c, blob, size, &st) == fmi2OK);
        check("set state into a fresh instance", st && fmi2SetFMUstate(c, st) == fmi2OK);
        check("second half", run(c, half, steps, dt, rows));
        fmi2FreeFMUstate(c, &st);
        finish(c, argv[5], rows, steps);
        free(rows);
        free(again);
        return g_failures ? 1 : 0;
    }
    check("initialise", fmi2SetupExperiment(c, fmi2False, 0, 0.0, fmi2False, 0) == fmi2OK &&
                        fmi2EnterInitializationMode(c) == fmi2OK);
    for (const char *s = argc == 9 ? argv[8] : NULL; s && *s;) {   /* VR=VALUE,... */
        char *end;
        fmi2ValueReference vr = (fmi2ValueReference)strtoul(s, &end, 10);
        fmi2Integer value = *end == '=' ? (fmi2Integer)strtol(end + 1, &end, 10) : 0;
        check("set integer", fmi2SetInteger(c, &vr, 1, &value) == fmi2OK);
        s = *end == ',' ? end + 1 : NULL;
    }
    check("initialised", 
                        fmi2ExitInitializationMode(c) == fmi2OK);
    check("first half", run(c, 0, half, dt, rows));
    g_steps_time = now() - g_first_done;
    fmi2FMUstate st = NULL, st2 = NULL;
    size_t size = 0;
    check("get state", fmi2GetFMUstate(c, &st) == fmi2OK);
    check("state size", fmi2SerializedFMUstateSize(c, st, &size) == fmi2OK && size > 0);
    fmi2Byte *bytes = malloc(size);
    check("serialise", bytes && fmi2SerializeFMUstate(c, st, bytes, size) == fmi2OK);
    check("deserialise", fmi2DeSerializeFMUstate(c, bytes, size, &st2) == fmi2OK);
    const char *state_out = getenv("FMU_RUN_STATE_OUT");
    if (state_out && bytes) {
        FILE *f = fopen(state_out, "wb");
        check("write state", f && fwrite(bytes, 1, size, f) == size);
        if (f) fclose(f);
    }
    check("second half", run(c, half, steps, dt, rows));
    check("set state", fmi2SetFMUstate(c, st2) == fmi2OK);
    check("second half again", run(c, half, steps, dt, again));
    check("rollback bit for bit",
          memcmp(rows + (size_t)half * g_nout, again + (size_t)half * g_nout,
                 sizeof *rows * (size_t)(steps - half) * g_nout) == 0);
    fmi2FreeFMUstate(c, &st);
    fmi2FreeFMUstate(c, &st2);
    free(bytes);
    finish(c, argv[5], rows, steps);
    int py = python_loaded();
    printf("python-in-process %s\n", py == 0 ? "no" : py > 0 ? "yes" : "unknown");
    printf("time load-to-first-step-s %.6f\n", g_first_done - t_start);
    printf("time per-step-us %.3f\n", 1e6 * g_steps_time / (half - 1));
    free(rows);
    free(again);
    return g_failures ? 1 : 0;
}
