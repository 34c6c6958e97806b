/* Runs the prebuilt kernel (fmu_src/aot.py: kernel.step, int32_t step(double **args)) from a
   saved set of its arrays, the same source on Linux (dlopen) and on Windows (LoadLibraryW;
   cross-compiled with mingw-w64, run under wine by tests/test_win64.py), so that the two
   libraries are compared on the same state.

   usage: step_driver LIBRARY SYMBOL ARRAYS STEPS OUT   (ARRAYS and OUT: ASCII paths)
   ARRAYS: "TTARR1\0\0", int32 count, int32 index of the output array, then per array an int64
   length and that many doubles (little-endian).  Steps STEPS times; writes to OUT, per step,
   the int32 return code and the output array. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef _WIN32
#include <windows.h>
#include <shellapi.h>
/* The library's path as Windows hands it, UTF-16 (argv is in the ANSI code page, which cannot
   hold every name): the program's own command line, split. */
static void *open_library(const char *ansi)
{
    (void)ansi;
    int n = 0;
    wchar_t **wargv = CommandLineToArgvW(GetCommandLineW(), &n);
    void *lib = (wargv && n > 1) ? (void *)LoadLibraryW(wargv[1]) : NULL;
    LocalFree(wargv);
    return lib;
}
static void *find_symbol(void *lib, const char *name)
{
    return (void *)GetProcAddress((HMODULE)lib, name);
}
#else
#include <dlfcn.h>
static void *open_library(const char *path) { return dlopen(path, RTLD_NOW | RTLD_LOCAL); }
static void *find_symbol(void *lib, const char *name) { return dlsym(lib, name); }
#endif

typedef int32_t (*step_fn)(double **);

static int fail(const char *what)
{
    fprintf(stderr, "step_driver: %s\n", what);
    return 2;
}

int main(int argc, char **argv)
{
    if (argc != 6) return fail("usage: step_driver LIBRARY SYMBOL ARRAYS STEPS OUT");
    void *lib = open_library(argv[1]);
    if (!lib) return fail("cannot load the library");
    step_fn step = (step_fn)find_symbol(lib, argv[2]);
    if (!step) return fail("no such symbol");
    FILE *f = fopen(argv[3], "rb");
    if (!f) return fail("cannot open the arrays");
    char magic[8];
    int32_t count, out_index;
    if (fread(magic, 1, 8, f) != 8 || memcmp(magic, "TTARR1\0\0", 8) != 0 ||
        fread(&count, 4, 1, f) != 1 || fread(&out_index, 4, 1, f) != 1 ||
        count <= 0 || count > 64 || out_index < 0 || out_index >= count)
        return fail("bad arrays file");
    double *arrays[64];
    int64_t lengths[64];
    for (int i = 0; i < count; ++i) {
        if (fread(&lengths[i], 8, 1, f) != 1 || lengths[i] <= 0 || lengths[i] > (1 << 24))
            return fail("bad array length");
        arrays[i] = malloc((size_t)lengths[i] * sizeof(double));
        if (!arrays[i] || fread(arrays[i], 8, (size_t)lengths[i], f) != (size_t)lengths[i])
            return fail("short arrays file");
    }
    fclose(f);
    long steps = strtol(argv[4], NULL, 10);
    FILE *out = fopen(argv[5], "wb");
    if (!out) return fail("cannot write the output");
    for (long k = 0; k < steps; ++k) {
        int32_t rc = step(arrays);
        fwrite(&rc, 4, 1, out);
        fwrite(arrays[out_index], 8, (size_t)lengths[out_index], out);
    }
    fclose(out);
    for (int i = 0; i < count; ++i) free(arrays[i]);
    return 0;
}
