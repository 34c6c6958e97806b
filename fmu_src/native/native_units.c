/* A step whose units are independent (a joint's needle-resolved rollers with the spider
   prescribed: each reads and writes only its own slices of the arrays) runs them at once, one
   thread a core, each joined before the step returns: the layer's only platform code.  The
   bits are those of model_step's units one after the other, in any order. */
#ifndef _WIN32
#define _POSIX_C_SOURCE 200809L   /* sysconf under -std=c99 */
#endif
#include <fenv.h>
#include <stddef.h>

#include "native_model.h"
#include "native_units.h"

#ifdef _WIN32
#include <windows.h>
#else
#include <pthread.h>
#include <unistd.h>
#endif

enum { MAX_WORKERS = 8, UNITS_NEXT = 4 };   /* UNITS_NEXT: model_step_begin's "the units now" */

typedef struct {
    const fenv_t *env;       /* the calling thread's floating-point environment */
    double *args[A_COUNT];   /* the instance's arrays, TH its own: the unit's index */
    double th[2];
    int first, stride, n;    /* its units: first, first + stride, ... below n */
    int32_t rc;              /* 1: each returned 1; 3: one ran out of its budget; 0: an error */
} Worker;

static void run_worker(Worker *w)
{
    w->rc = 1;
    for (int i = w->first; i < w->n; i += w->stride) {
        w->th[0] = (double)i;
        int32_t rc = model_step_unit(w->args);
        if (rc == 0) {
            w->rc = 0;
            return;
        }
        if (rc != 1) w->rc = 3;
    }
}

/* A thread starts in the caller's floating-point environment: on Windows a new thread's x87
   precision control is 53 bits where the main thread's is 64, and the win64 binary's math then
   gave another last bit on the new thread (a roller's pressing offset, one ulp: the FMU refused
   its own state). */
static void worker_run(Worker *w)
{
    fesetenv(w->env);
    run_worker(w);
}

#ifdef _WIN32
static DWORD WINAPI worker_main(LPVOID p) { worker_run((Worker *)p); return 0; }
static int cores(void)
{
    SYSTEM_INFO si;
    GetSystemInfo(&si);
    return (int)si.dwNumberOfProcessors;
}
#else
static void *worker_main(void *p) { worker_run((Worker *)p); return NULL; }
static int cores(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n > 0 ? (int)n : 1;
}
#endif

int32_t native_step_units(double **args, int n)
{
    int k = cores();
    if (k > n) k = n;
    if (k > MAX_WORKERS) k = MAX_WORKERS;
    if (k < 2) return model_step(args);
    int32_t rc = model_step_begin(args);
    if (rc != UNITS_NEXT) return rc;
    fenv_t env;
    fegetenv(&env);
    Worker w[MAX_WORKERS];
    for (int j = 0; j < k; ++j) {
        w[j].env = &env;
        for (int a = 0; a < A_COUNT; ++a) w[j].args[a] = args[a];
        w[j].args[A_TH] = w[j].th;
        w[j].th[0] = w[j].th[1] = 0.0;
        w[j].first = j, w[j].stride = k, w[j].n = n;
    }
    /* worker 0 here, the others on threads; one whose thread did not start, here after */
#ifdef _WIN32
    HANDLE t[MAX_WORKERS] = {0};
    for (int j = 1; j < k; ++j) t[j] = CreateThread(NULL, 0, worker_main, &w[j], 0, NULL);
    run_worker(&w[0]);
    for (int j = 1; j < k; ++j) {
        if (t[j]) {
            WaitForSingleObject(t[j], INFINITE);
            CloseHandle(t[j]);
        } else {
            run_worker(&w[j]);
        }
    }
#else
    pthread_t t[MAX_WORKERS];
    int started[MAX_WORKERS] = {0};
    for (int j = 1; j < k; ++j) started[j] = pthread_create(&t[j], NULL, worker_main, &w[j]) == 0;
    run_worker(&w[0]);
    for (int j = 1; j < k; ++j) {
        if (started[j]) pthread_join(t[j], NULL);
        else run_worker(&w[j]);
    }
#endif
    double ok[2] = {1.0, 0.0};
    for (int j = 0; j < k; ++j) {
        if (w[j].rc == 0) return 0;
        if (w[j].rc != 1) ok[0] = 0.0;
    }
    double *fa[A_COUNT];
    for (int a = 0; a < A_COUNT; ++a) fa[a] = args[a];
    fa[A_TH] = ok;
    return model_step_finish(fa);
}
