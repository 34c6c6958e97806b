/* What fmi2_native.c needs of a model compiled ahead of time: its variables (generated at build
   time from the parameter table and the model description: fmu_src/native_fmu.py), the sizes of
   its arrays, and its two compiled functions (the model's Python, compiled by fmu_src/aot.py).
   Plain data: no Python, no platform. */
#ifndef NATIVE_MODEL_H
#define NATIVE_MODEL_H

#include <stdint.h>

/* where a variable's value lives: the model's arrays P (parameters, integers as doubles), IN
   (inputs), OUT (outputs) */
enum { IN_P, IN_IN, IN_OUT };

typedef struct {
    const char *name;
    uint32_t vr;
    char type;           /* 'R' Real, 'I' Integer */
    int array;           /* IN_P, IN_IN, IN_OUT */
    int slot;            /* index in that array */
    double start;
    /* the table's range (check_param): lo, hi (has_lo/has_hi), open ends, "0 or at least" */
    int has_lo, has_hi, lo_open, hi_open;
    double lo, hi, auto_or_min;   /* auto_or_min 0: none */
    const char *range_text;       /* Param.range_text(), for the messages */
} ModelVar;

/* the arrays the compiled functions take, in this order: P, IN, X, OUT, W, TH (t, h) */
enum { A_P, A_IN, A_X, A_OUT, A_W, A_TH, A_COUNT };

extern const char MODEL_ID[];
extern const char MODEL_GUID[];
extern const ModelVar MODEL_VARS[];
extern const int MODEL_N_VARS;
extern const int MODEL_CHECK_ORDER[];    /* the variables checked at initialisation, in order */
extern const int MODEL_N_CHECK;
extern const int MODEL_SIZES[A_COUNT];   /* doubles in each array */

/* 1: done; 2: a non-finite output (OUT untouched); -(1 + slot): the parameter P[slot] cannot
   be divided by (init only); 0: an error inside the compiled code */
int32_t model_init(double **args);
int32_t model_step(double **args);

#endif
