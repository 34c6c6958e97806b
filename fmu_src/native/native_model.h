/* What fmi2_native.c needs of a model compiled ahead of time: its variables (generated at build
   time from the parameter table and the model description: fmu_src/native_fmu.py), the sizes of
   its arrays, and its two compiled functions (the model's Python, compiled by fmu_src/aot.py).
   Plain data: no Python, no platform. */
#ifndef NATIVE_MODEL_H
#define NATIVE_MODEL_H

#include <stdint.h>

/* where a variable's value lives: the model's arrays T (the parameter table, integers as
   doubles), IN (inputs), OUT (outputs) */
enum { IN_T, IN_IN, IN_OUT };

typedef struct {
    const char *name;
    uint32_t vr;
    char type;           /* 'R' Real, 'I' Integer, 'B' Boolean (0 or 1) */
    int array;           /* IN_T, IN_IN, IN_OUT */
    int slot;            /* index in that array */
    double start;
    /* the table's range (check_param): lo, hi (has_lo/has_hi), open ends, "0 or at least" */
    int has_lo, has_hi, lo_open, hi_open;
    double lo, hi, auto_or_min;   /* auto_or_min 0: none */
    const char *range_text;       /* Param.range_text(), for the messages */
} ModelVar;

/* the arrays the compiled functions take, in this order: T, IN, X, OUT, W, TH (t, h) */
enum { A_T, A_IN, A_X, A_OUT, A_W, A_TH, A_COUNT };

extern const char MODEL_ID[];
extern const char MODEL_GUID[];
extern const ModelVar MODEL_VARS[];
extern const int MODEL_N_VARS;
/* MODEL_VARS' index of the variable with value reference vr < MODEL_N_BY_VR (-1: none, or
   more than one: then searched) */
extern const int MODEL_BY_VR[];
extern const int MODEL_N_BY_VR;
extern const int MODEL_CHECK_ORDER[];    /* the variables checked at initialisation, in order */
extern const int MODEL_N_CHECK;
extern const int MODEL_SIZES[A_COUNT];   /* doubles in each array */

/* The notes a compiled function leaves for the log in W (MODEL_NOTES_AT < 0: none): a count,
   then per note its code and MODEL_NOTE_ARGS numbers; MODEL_NOTE_TEXT[code] words it (a printf
   format of the numbers, at a level: 0 info, 1 warning, 2 error).  A text starting with "; "
   continues the message before it. */
typedef struct { int level; const char *text; } ModelNote;
extern const ModelNote MODEL_NOTE_TEXT[];
extern const int MODEL_N_NOTE_TEXT, MODEL_NOTES_AT, MODEL_NOTE_ARGS, MODEL_MAX_NOTES;
/* why model_check_state refuses a state: MODEL_STATE_PROBLEMS[code] */
extern const char *const MODEL_STATE_PROBLEMS[];
extern const int MODEL_N_STATE_PROBLEMS;

/* 1: done; 2: a non-finite output (OUT untouched); 3: refused, its notes say why; 5 (step): an
   input the model derived (written into IN) is outside its range, nothing stepped; -(1 +
   slot): the parameter T[slot] cannot be divided by (init only); 0: an error inside the
   compiled code */
int32_t model_init(double **args);
int32_t model_step(double **args);
/* the run's end (notes only): 1 */
int32_t model_end(double **args);
/* A step in parts, where it has independent units (a joint's needle-resolved rollers):
   model_step_units(args) of them (0: model_step takes every step whole);
   model_step_begin(args) as model_step until the units: 4 when they are next, else
   model_step's code; model_step_unit(args) with TH[0] the unit's index: 1, 3 out of its budget
   (0 an error), each unit reading and writing only its own slices; model_step_finish(args)
   with TH[0] 1.0 when every unit returned 1: model_step's code (native_units.c) */
int32_t model_step_units(double **args);
int32_t model_step_begin(double **args);
int32_t model_step_unit(double **args);
int32_t model_step_finish(double **args);
/* 0: the state's arrays (args) can be stepped; else a code of MODEL_STATE_PROBLEMS */
int32_t model_check_state(double **args);

#endif
