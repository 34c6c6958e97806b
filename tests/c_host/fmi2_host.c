/*
 * A plain C co-simulation host, as Simulink, Dymola or GT-SUITE load an FMU: dlopen the FMU's
 * binary (no libpython linked or preloaded), instantiate, initialise, step, read, get/set and
 * serialise the FMU state, free, dlclose, and do it all again, the second time from another
 * thread.  Built and run by tests/test_native.py.
 *
 * usage: fmi2_host UNZIPPED_FMU MODEL_ID GUID VR_OUT STOP STEP OUT_FILE [VR_INT=VALUE ...]
 *   Writes the output VR_OUT after every step of the first round to OUT_FILE (%.17g a line)
 *   and prints one line per check: "check NAME ok|FAILED ...".  Exit status 0 when every
 *   check held.  With VR_INT=VALUE, integer start values (e.g. an invalid bearing): it then
 *   reports the status of fmi2ExitInitializationMode and stops.
 */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <math.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi2Functions.h"

typedef struct {
    void *lib;
#define F(name) name##TYPE *name;
    F(fmi2Instantiate) F(fmi2FreeInstance) F(fmi2SetupExperiment) F(fmi2EnterInitializationMode)
    F(fmi2ExitInitializationMode) F(fmi2Terminate) F(fmi2DoStep) F(fmi2GetReal) F(fmi2SetInteger)
    F(fmi2GetFMUstate) F(fmi2SetFMUstate) F(fmi2FreeFMUstate) F(fmi2SerializedFMUstateSize)
    F(fmi2SerializeFMUstate) F(fmi2DeSerializeFMUstate) F(fmi2GetBooleanStatus)
#undef F
} Api;

static const char *g_dir, *g_id, *g_guid, *g_out_file;
static fmi2ValueReference g_vr;
static double g_stop, g_step;
static int g_n_ints, g_failures;
static fmi2ValueReference g_int_vr[8];
static fmi2Integer g_int_val[8];
static int g_log_errors;

static void logger(fmi2ComponentEnvironment env, fmi2String name, fmi2Status status,
                   fmi2String category, fmi2String message, ...)
{
    (void)env;
    va_list ap;
    va_start(ap, message);
    fprintf(stderr, "[%s|%d|%s] ", name, (int)status, category ? category : "");
    vfprintf(stderr, message, ap);     /* the FMI logger's message is a printf format */
    fputc('\n', stderr);
    va_end(ap);
    if (status >= fmi2Error) g_log_errors++;
}

static void check(const char *name, int ok, const char *detail)
{
    printf("check %s %s%s%s\n", name, ok ? "ok" : "FAILED", detail ? " " : "", detail ? detail : "");
    if (!ok) g_failures++;
}

static int load(Api *a, char *so_path)
{
    memset(a, 0, sizeof *a);
    a->lib = dlopen(so_path, RTLD_NOW | RTLD_LOCAL);
    if (!a->lib) {
        fprintf(stderr, "dlopen: %s\n", dlerror());
        return 0;
    }
#define F(name) if (!(*(void **)(&a->name) = dlsym(a->lib, #name))) { fprintf(stderr, "missing %s\n", #name); return 0; }
    F(fmi2Instantiate) F(fmi2FreeInstance) F(fmi2SetupExperiment) F(fmi2EnterInitializationMode)
    F(fmi2ExitInitializationMode) F(fmi2Terminate) F(fmi2DoStep) F(fmi2GetReal) F(fmi2SetInteger)
    F(fmi2GetFMUstate) F(fmi2SetFMUstate) F(fmi2FreeFMUstate) F(fmi2SerializedFMUstateSize)
    F(fmi2SerializeFMUstate) F(fmi2DeSerializeFMUstate) F(fmi2GetBooleanStatus)
#undef F
    return 1;
}

static fmi2Component instantiate(Api *a, const char *name)
{
    static fmi2CallbackFunctions cb = {logger, calloc, free, NULL, NULL};
    char uri[4200];
    snprintf(uri, sizeof uri, "file://%s/resources", g_dir);
    return a->fmi2Instantiate(name, fmi2CoSimulation, g_guid, uri, &cb, fmi2False, fmi2False);
}

/* Communication points as FMPy makes them: t_i = i h, each step t_(i+1) - t_i. */
static double t_at(int i) { return i * g_step; }

/* Steps i0 .. i0+n-1, the output after each into y (may be NULL); 0 on a non-OK status */
static int steps(Api *a, fmi2Component c, int i0, int n, double *y)
{
    for (int i = i0; i < i0 + n; ++i) {
        if (a->fmi2DoStep(c, t_at(i), t_at(i + 1) - t_at(i), fmi2True) != fmi2OK) return 0;
        double v;
        if (a->fmi2GetReal(c, &g_vr, 1, &v) != fmi2OK) return 0;
        if (y) y[i] = v;
    }
    return 1;
}

/* One round: a whole run to g_stop with a state taken halfway, then the second half again
   from the state and from its serialised copy: each must repeat the outputs bit for bit. */
static int round_(Api *a, double *y)
{
    int n = (int)(g_stop / g_step + 0.5), half = n / 2, ok = 1;
    fmi2Component c = instantiate(a, "roller");
    if (!c) return 0;
    ok &= a->fmi2SetupExperiment(c, fmi2False, 0.0, 0.0, fmi2True, g_stop) == fmi2OK;
    ok &= a->fmi2EnterInitializationMode(c) == fmi2OK;
    ok &= a->fmi2ExitInitializationMode(c) == fmi2OK;
    fmi2FMUstate st = NULL, st2 = NULL;
    ok &= steps(a, c, 0, half, y);
    ok &= a->fmi2GetFMUstate(c, &st) == fmi2OK;
    ok &= steps(a, c, half, n - half, y);
    double *again = calloc((size_t)n, sizeof *again), *third = calloc((size_t)n, sizeof *third);
    ok &= a->fmi2SetFMUstate(c, st) == fmi2OK;
    ok &= steps(a, c, half, n - half, again);
    size_t size = 0;
    ok &= a->fmi2SerializedFMUstateSize(c, st, &size) == fmi2OK;
    char *bytes = malloc(size);
    ok &= a->fmi2SerializeFMUstate(c, st, bytes, size) == fmi2OK;
    ok &= a->fmi2DeSerializeFMUstate(c, bytes, size, &st2) == fmi2OK;
    ok &= a->fmi2SetFMUstate(c, st2) == fmi2OK;
    ok &= steps(a, c, half, n - half, third);
    check("state_rollback_bitwise", ok && !memcmp(y + half, again + half, (size_t)(n - half) * sizeof *y), NULL);
    check("serialized_state_bitwise", ok && !memcmp(y + half, third + half, (size_t)(n - half) * sizeof *y), NULL);
    a->fmi2FreeFMUstate(c, &st);
    a->fmi2FreeFMUstate(c, &st2);
    check("state_freed", st == NULL && st2 == NULL, NULL);
    ok &= a->fmi2Terminate(c) == fmi2OK;
    a->fmi2FreeInstance(c);
    free(bytes);
    free(again);
    free(third);
    return ok;
}

typedef struct { Api *a; double *y; int ok; } Job;

static void *thread_round(void *p)
{
    Job *j = p;
    j->ok = round_(j->a, j->y);
    return NULL;
}

/* Invalid integer start values: fmi2ExitInitializationMode must say fmi2Error (not Fatal)
   and the instance must still free cleanly. */
static int invalid_start(Api *a)
{
    fmi2Component c = instantiate(a, "invalid");
    if (!c) return 1;
    a->fmi2SetupExperiment(c, fmi2False, 0.0, 0.0, fmi2False, 0.0);
    a->fmi2EnterInitializationMode(c);
    fmi2Status set = a->fmi2SetInteger(c, g_int_vr, (size_t)g_n_ints, g_int_val);
    fmi2Status st = a->fmi2ExitInitializationMode(c);
    printf("exit_initialization_status %d (set %d)\n", (int)st, (int)set);
    fmi2Status step = a->fmi2DoStep(c, 0.0, g_step, fmi2True);
    printf("do_step_after_failed_init_status %d\n", (int)step);
    a->fmi2FreeInstance(c);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc < 8) {
        fprintf(stderr, "usage: %s DIR MODEL_ID GUID VR_OUT STOP STEP OUT_FILE [VR=INT ...]\n", argv[0]);
        return 2;
    }
    g_dir = argv[1], g_id = argv[2], g_guid = argv[3], g_vr = (fmi2ValueReference)atol(argv[4]);
    g_stop = atof(argv[5]), g_step = atof(argv[6]), g_out_file = argv[7];
    for (int i = 8; i < argc && g_n_ints < 8; ++i, ++g_n_ints)
        sscanf(argv[i], "%u=%d", &g_int_vr[g_n_ints], &g_int_val[g_n_ints]);
    char so[4200];
    snprintf(so, sizeof so, "%s/binaries/linux64/%s.so", g_dir, g_id);
    Api a;
    if (!load(&a, so)) return 1;
    if (g_n_ints) return invalid_start(&a);

    int n = (int)(g_stop / g_step + 0.5);
    double *y1 = calloc((size_t)n, sizeof *y1), *y2 = calloc((size_t)n, sizeof *y2);
    check("first_round", round_(&a, y1), NULL);
    FILE *f = fopen(g_out_file, "w");
    for (int i = 0; f && i < n; ++i) fprintf(f, "%.17g\n", y1[i]);
    if (f) fclose(f);

    /* unload: the library must really leave the process (no NODELETE, nothing of it kept) */
    check("dlclose", dlclose(a.lib) == 0, NULL);
    void *still = dlopen(so, RTLD_NOW | RTLD_NOLOAD);
    check("unloaded", still == NULL, NULL);
    if (still) dlclose(still);

    /* load again, and run from a thread that is not the one that loaded it or started Python */
    if (!load(&a, so)) return 1;
    Job j = {&a, y2, 0};
    pthread_t t;
    pthread_create(&t, NULL, thread_round, &j);
    pthread_join(t, NULL);
    check("second_round_from_thread", j.ok, NULL);
    check("rounds_bitwise_equal", !memcmp(y1, y2, (size_t)n * sizeof *y1), NULL);

    /* two instances at once, stepped alternately, agree with the single run */
    fmi2Component c1 = instantiate(&a, "one"), c2 = instantiate(&a, "two");
    int ok = c1 && c2;
    for (fmi2Component *c = (fmi2Component[]){c1, c2, NULL}; ok && *c; ++c)
        ok &= a.fmi2SetupExperiment(*c, fmi2False, 0.0, 0.0, fmi2False, 0.0) == fmi2OK &&
              a.fmi2EnterInitializationMode(*c) == fmi2OK && a.fmi2ExitInitializationMode(*c) == fmi2OK;
    double v1 = 0, v2 = 0;
    int m = n < 200 ? n : 200;
    for (int i = 0; ok && i < m; ++i) {
        ok &= a.fmi2DoStep(c1, t_at(i), t_at(i + 1) - t_at(i), fmi2True) == fmi2OK;
        ok &= a.fmi2DoStep(c2, t_at(i), t_at(i + 1) - t_at(i), fmi2True) == fmi2OK;
        ok &= a.fmi2GetReal(c1, &g_vr, 1, &v1) == fmi2OK && a.fmi2GetReal(c2, &g_vr, 1, &v2) == fmi2OK;
        ok &= v1 == y1[i] && v2 == y1[i];
    }
    check("two_instances", ok, NULL);
    if (c1) a.fmi2FreeInstance(c1);
    if (c2) a.fmi2FreeInstance(c2);

    /* a variable-step master: the step size changes every step (0.5 to 1.5 of the step);
       two instances stepped alternately agree bit for bit, every output finite */
    c1 = instantiate(&a, "vary1"), c2 = instantiate(&a, "vary2");
    ok = c1 && c2;
    for (fmi2Component *c = (fmi2Component[]){c1, c2, NULL}; ok && *c; ++c)
        ok &= a.fmi2SetupExperiment(*c, fmi2False, 0.0, 0.0, fmi2False, 0.0) == fmi2OK &&
              a.fmi2EnterInitializationMode(*c) == fmi2OK && a.fmi2ExitInitializationMode(*c) == fmi2OK;
    double tc = 0.0;
    for (int i = 0; ok && i < m; ++i) {
        double h = g_step * (0.5 + (double)((i * 7919) % 13) / 12.0);
        ok &= a.fmi2DoStep(c1, tc, h, fmi2True) == fmi2OK && a.fmi2DoStep(c2, tc, h, fmi2True) == fmi2OK;
        ok &= a.fmi2GetReal(c1, &g_vr, 1, &v1) == fmi2OK && a.fmi2GetReal(c2, &g_vr, 1, &v2) == fmi2OK;
        ok &= v1 == v2 && isfinite(v1);
        tc += h;
    }
    check("varying_steps", ok, NULL);
    if (c1) a.fmi2FreeInstance(c1);
    if (c2) a.fmi2FreeInstance(c2);
    check("no_error_logged", g_log_errors == 0, NULL);
    check("dlclose_again", dlclose(a.lib) == 0, NULL);
    free(y1);
    free(y2);
    printf("%d failed\n", g_failures);
    return g_failures ? 1 : 0;
}
