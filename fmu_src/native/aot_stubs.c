/* What a model compiled ahead of time (fmu_src/aot.py) references besides libm: numba's runtime and the
   Python C API, on its error path only (a division by zero raising inside the compiled step).
   Stubbed here, hidden, so the library loads in any host, with or without Python symbols, and
   an error makes the step return 0 (the native layer reports it) instead of
   raising.  Nothing on the normal path calls them.  (A Windows DLL must resolve every symbol
   when it is linked: the list is the cross-built object's undefined symbols but libm's.) */
#include <stddef.h>
#include <stdint.h>

#ifdef _WIN32
#define HIDDEN          /* a DLL exports only what is marked for it */
#else
#define HIDDEN __attribute__((visibility("hidden")))
#endif

HIDDEN void *PyExc_RuntimeError = NULL;
HIDDEN void *PyExc_StopIteration = NULL;
HIDDEN void *PyExc_SystemError = NULL;

HIDDEN void numba_gil_ensure(void *state) { (void)state; }
HIDDEN void numba_gil_release(void *state) { (void)state; }
HIDDEN void numba_do_raise(void *excinfo) { (void)excinfo; }
HIDDEN void *numba_unpickle(const char *data, int32_t n, const char *hash)
{
    (void)data; (void)n; (void)hash;
    return NULL;
}
HIDDEN void *numba_runtime_build_excinfo_struct(void *a, void *b)
{
    (void)a; (void)b;
    return NULL;
}
HIDDEN void NRT_Free(void *p) { (void)p; }
HIDDEN void NRT_MemInfo_call_dtor(void *mi) { (void)mi; }
HIDDEN void *PyUnicode_FromString(const char *s) { (void)s; return NULL; }
HIDDEN void *PyBytes_FromStringAndSize(const char *s, int64_t n) { (void)s; (void)n; return NULL; }
HIDDEN void PyErr_WriteUnraisable(void *o) { (void)o; }
HIDDEN void PyErr_SetString(void *t, const char *s) { (void)t; (void)s; }
HIDDEN void PyErr_SetNone(void *t) { (void)t; }
HIDDEN void PyErr_Clear(void) {}
HIDDEN void Py_DecRef(void *o) { (void)o; }
