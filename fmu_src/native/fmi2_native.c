/* The FMI 2.0 co-simulation functions and call states for a model compiled ahead of time: the
   whole lifecycle without Python, in plain C99 over libc and libm, the same source for Linux
   and Windows (nothing here is platform code: no loading, no paths, no threads).  In parts:
   - this file: the FMI functions, the call sequence (the Reference-FMUs' masks), the instance
     and the FMU state's copies, the model's notes logged;
   - native_model.h: the binding to a compiled model (its variables, generated at build time
     from the parameter table into model_data.c, its sizes, its four functions);
   - native_values.c: values checked and worded as reduced_model/scene.py's check_param does;
   - native_state.c: the FMU state serialised as checked data (magic, sizes, GUID, CRC-32),
     nothing in it sizing an allocation;
   - native_units.c: a step's independent units (a joint's needle-resolved rollers) run at once
     on the machine's cores, the only platform code (threads, each joined within the step).
   Each instance owns its memory; no global state, no thread outlives a call, nothing at exit. */
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi2Functions.h"
#include "native_model.h"
#include "native_state.h"
#include "native_units.h"
#include "native_values.h"

typedef enum { INSTANTIATED, INIT_MODE, STEP_COMPLETE, STEP_FAILED, TERMINATED, ERRORED } Phase;
static const char *const PHASE_NAMES[] = {"instantiated", "initialization mode",
                                          "step complete", "step failed", "terminated",
                                          "error"};
enum {
    P_INST = 1 << INSTANTIATED, P_INIT = 1 << INIT_MODE, P_OK = 1 << STEP_COMPLETE,
    P_FAILED = 1 << STEP_FAILED, P_TERM = 1 << TERMINATED, P_ERR = 1 << ERRORED,
    P_ANY = P_INST | P_INIT | P_OK | P_FAILED | P_TERM | P_ERR
};

typedef struct {
    char *name;
    fmi2CallbackFunctions cb;
    int logging_on;
    Phase phase;
    double last_ok_time;
    int wants_to_terminate;
    double host_tolerance;         /* fmi2SetupExperiment's tolerance; 0: none given */
    double *data;                  /* every array, one block: the state's arrays, then W */
    double *arr[A_COUNT];
    size_t n_data;                 /* doubles in the block */
    size_t n_state;                /* of them, an FMU state's: all but W (work and notes) */
} Inst;

typedef struct {
    Phase phase;
    double last_ok_time;
    int wants_to_terminate;
    double *data;                  /* the instance's first n_state doubles */
    size_t n_data;
} State;

/* ---- messages ----------------------------------------------------------------------------- */

static void logf_(Inst *c, fmi2Status status, const char *fmt, ...)
{
    if (!c || !c->cb.logger || (status < fmi2Warning && !c->logging_on)) return;
    char msg[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    const char *cat = status >= fmi2Error ? "logStatusError" :
                      status == fmi2Warning ? "logStatusWarning" : "logAll";
    /* the logger's message is a printf format (FMI 2.0): ours goes in as an argument */
    c->cb.logger(c->cb.componentEnvironment, c->name, status, cat, "%s", msg);
}

/* ---- the model's notes (native_model.h) ----------------------------------------------------- */

static void say(Inst *c, int level, const char *prefix, const char *msg)
{
    if (level >= 2) logf_(c, fmi2Error, "%s%s", prefix, msg);
    else logf_(c, level == 1 ? fmi2Warning : fmi2OK, "%s", msg);
}

/* The notes the last compiled call left in W, worded and logged (errors after prefix); the
   count and codes are the model's, checked before use like any value of a state. */
static void log_notes_of(Inst *c, const double *work, const char *prefix)
{
    if (MODEL_NOTES_AT < 0) return;
    const double *W = work + MODEL_NOTES_AT;
    double count = W[0];
    int n = count >= 0.0 && count <= (double)MODEL_MAX_NOTES ? (int)count : 0;
    char msg[1024] = "", part[512];
    int level = 0;
    for (int k = 0; k < n; ++k) {
        const double *note = W + 1 + k * (1 + MODEL_NOTE_ARGS);
        if (!(note[0] >= 0.0 && note[0] < (double)MODEL_N_NOTE_TEXT)) continue;
        const ModelNote *m = &MODEL_NOTE_TEXT[(int)note[0]];
        double a[4] = {0.0, 0.0, 0.0, 0.0};
        for (int i = 0; i < MODEL_NOTE_ARGS && i < 4; ++i) a[i] = note[1 + i];
        snprintf(part, sizeof part, m->text, a[0], a[1], a[2], a[3]);
        if (strncmp(part, "; ", 2) == 0 && msg[0]) {      /* continues the message before */
            size_t len = strlen(msg);
            const char *add = len >= 2 && strcmp(msg + len - 2, ": ") == 0 ? part + 2 : part;
            strncat(msg, add, sizeof msg - len - 1);
            continue;
        }
        if (msg[0]) say(c, level, prefix, msg);
        snprintf(msg, sizeof msg, "%s", part);
        level = m->level;
    }
    if (msg[0]) say(c, level, prefix, msg);
}

static void log_notes(Inst *c, const char *prefix) { log_notes_of(c, c->arr[A_W], prefix); }

/* ---- the call sequence -------------------------------------------------------------------- */

static int allowed(Inst *c, const char *fn, unsigned phases)
{
    if (phases & (1u << c->phase)) return 1;
    logf_(c, fmi2Error, "%s is not allowed in phase '%s'", fn, PHASE_NAMES[c->phase]);
    return 0;
}

static double *slot_of(Inst *c, const ModelVar *v)
{
    return &c->arr[v->array == IN_T ? A_T : v->array == IN_IN ? A_IN : A_OUT][v->slot];
}

/* Every variable at its start value, the model at rest. */
static void set_starts(Inst *c)
{
    memset(c->data, 0, c->n_data * sizeof *c->data);
    for (int k = 0; k < MODEL_N_VARS; ++k) *slot_of(c, &MODEL_VARS[k]) = MODEL_VARS[k].start;
}

/* ---- FMI 2.0: common functions ------------------------------------------------------------ */

const char *fmi2GetTypesPlatform(void) { return fmi2TypesPlatform; }
const char *fmi2GetVersion(void) { return fmi2Version; }

static void destroy(Inst *c)
{
    if (!c) return;
    free(c->data);
    free(c->name);
    free(c);
}

/* The arrays in one block: every one but W in A_ order (what an FMU state holds), then W (the
   model's work and notes, rebuilt by every call). */
static void place_arrays(double *arr[A_COUNT], double *data)
{
    size_t at = 0;
    for (int a = 0; a < A_COUNT; ++a)
        if (a != A_W) {
            arr[a] = data + at;
            at += (size_t)MODEL_SIZES[a];
        }
    arr[A_W] = data + at;
}

fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                              fmi2String fmuResourceLocation,
                              const fmi2CallbackFunctions *functions, fmi2Boolean visible,
                              fmi2Boolean loggingOn)
{
    (void)fmuResourceLocation;
    (void)visible;
    Inst *c = calloc(1, sizeof *c);
    if (!c) return NULL;
    const char *name = instanceName ? instanceName : "";
    c->name = malloc(strlen(name) + 1);
    if (c->name) strcpy(c->name, name);
    if (functions) c->cb = *functions;
    c->logging_on = loggingOn != fmi2False;
    size_t n = 0;
    for (int a = 0; a < A_COUNT; ++a) n += (size_t)MODEL_SIZES[a];
    c->n_data = n;
    c->n_state = n - (size_t)MODEL_SIZES[A_W];
    c->data = calloc(n, sizeof *c->data);
    if (!c->name || !c->data) {
        destroy(c);
        return NULL;
    }
    place_arrays(c->arr, c->data);
    if (fmuType != fmi2CoSimulation) {
        logf_(c, fmi2Error, "fmi2Instantiate: this FMU supports co-simulation only");
        destroy(c);
        return NULL;
    }
    if (!fmuGUID || strcmp(fmuGUID, MODEL_GUID) != 0) {
        logf_(c, fmi2Error, "fmi2Instantiate: GUID %s is not this FMU's %s",
              fmuGUID ? fmuGUID : "(null)", MODEL_GUID);
        destroy(c);
        return NULL;
    }
    set_starts(c);
    c->phase = INSTANTIATED;
    logf_(c, fmi2OK, "%s: compiled model, no Python", MODEL_ID);
    return c;
}

void fmi2FreeInstance(fmi2Component component) { destroy((Inst *)component); }

fmi2Status fmi2SetDebugLogging(fmi2Component component, fmi2Boolean loggingOn,
                               size_t nCategories, const fmi2String categories[])
{
    (void)nCategories;
    (void)categories;
    Inst *c = (Inst *)component;
    if (!c) return fmi2Error;
    c->logging_on = loggingOn != fmi2False;
    return fmi2OK;
}

fmi2Status fmi2SetupExperiment(fmi2Component component, fmi2Boolean toleranceDefined,
                               fmi2Real tolerance, fmi2Real startTime,
                               fmi2Boolean stopTimeDefined, fmi2Real stopTime)
{
    (void)stopTimeDefined;
    (void)stopTime;
    Inst *c = (Inst *)component;
    if (!c) return fmi2Error;
    if (!allowed(c, "fmi2SetupExperiment", P_INST)) return fmi2Error;
    if (!isfinite(startTime)) {
        logf_(c, fmi2Error, "fmi2SetupExperiment: startTime must be finite");
        return fmi2Error;
    }
    c->last_ok_time = startTime;
    c->host_tolerance = toleranceDefined && isfinite(tolerance) && tolerance > 0.0 ? tolerance
                                                                                  : 0.0;
    return fmi2OK;
}

/* The host's tolerance into the model's parameter "tolerance" where the model has one and it
   was left at 0 (automatic): clipped into its range, and said so. */
static void take_host_tolerance(Inst *c)
{
    if (!(c->host_tolerance > 0.0)) return;
    for (int k = 0; k < MODEL_N_VARS; ++k) {
        const ModelVar *v = &MODEL_VARS[k];
        if (v->array != IN_T || strcmp(v->name, "tolerance") != 0) continue;
        double *x = slot_of(c, v);
        if (*x != 0.0) return;        /* the user's own */
        double t = c->host_tolerance;
        if (v->auto_or_min > 0.0 && t < v->auto_or_min) t = v->auto_or_min;
        if (v->has_hi && t > v->hi) t = v->hi;
        *x = t;
        logf_(c, fmi2OK, "tolerance = %g: the host's %g (fmi2SetupExperiment)", t,
              c->host_tolerance);
        return;
    }
}

fmi2Status fmi2EnterInitializationMode(fmi2Component component)
{
    Inst *c = (Inst *)component;
    if (!c) return fmi2Error;
    if (!allowed(c, "fmi2EnterInitializationMode", P_INST)) return fmi2Error;
    c->phase = INIT_MODE;
    return fmi2OK;
}

/* Every parameter and start input checked, in the table's order; then the model's start. */
fmi2Status fmi2ExitInitializationMode(fmi2Component component)
{
    Inst *c = (Inst *)component;
    if (!c) return fmi2Error;
    if (!allowed(c, "fmi2ExitInitializationMode", P_INIT)) return fmi2Error;
    char why[512];
    take_host_tolerance(c);
    for (int i = 0; i < MODEL_N_CHECK; ++i) {
        const ModelVar *v = &MODEL_VARS[MODEL_CHECK_ORDER[i]];
        if (!native_value_ok(v, *slot_of(c, v), why, sizeof why)) {
            logf_(c, fmi2Error, "fmi2ExitInitializationMode: invalid parameter: %s", why);
            c->phase = ERRORED;
            return fmi2Error;
        }
    }
    int32_t rc = model_init(c->arr);
    if (rc == 1 || rc == 3) log_notes(c, "fmi2ExitInitializationMode: invalid parameter: ");
    if (rc < 0) {      /* a divisor too small: T[-rc - 1] */
        for (int k = 0; k < MODEL_N_VARS; ++k) {
            const ModelVar *v = &MODEL_VARS[k];
            if (v->array != IN_T || v->slot != -rc - 1) continue;
            char text[48];
            native_value_text(v, c->arr[A_T][v->slot], text, sizeof text);
            logf_(c, fmi2Error, "fmi2ExitInitializationMode: invalid parameter: %s = %s is too "
                  "small to compute with; allowed range %s", v->name, text, v->range_text);
        }
    } else if (rc != 1 && rc != 3) {
        logf_(c, fmi2Error, "fmi2ExitInitializationMode: invalid parameter: the start's "
              "outputs are not finite");
    }
    if (rc != 1) {
        c->phase = ERRORED;
        return fmi2Error;
    }
    c->phase = STEP_COMPLETE;
    return fmi2OK;
}

fmi2Status fmi2Terminate(fmi2Component component)
{
    Inst *c = (Inst *)component;
    if (!c) return fmi2Error;
    if (!allowed(c, "fmi2Terminate", P_OK | P_FAILED)) return fmi2Error;
    model_end(c->arr);
    log_notes(c, "fmi2Terminate: ");
    c->phase = TERMINATED;
    return fmi2OK;
}

fmi2Status fmi2Reset(fmi2Component component)
{
    Inst *c = (Inst *)component;
    if (!c) return fmi2Error;
    set_starts(c);
    c->phase = INSTANTIATED;
    c->last_ok_time = 0.0;
    c->wants_to_terminate = 0;
    return fmi2OK;
}

/* ---- variables ---------------------------------------------------------------------------- */

static const ModelVar *find(Inst *c, const char *fn, fmi2ValueReference vr, char type)
{
    /* (a table by value reference, generated: a master's getReal of every output each step
       costs a look-up each, not a search) */
    if (vr < (fmi2ValueReference)MODEL_N_BY_VR) {
        int k = MODEL_BY_VR[vr];
        if (k >= 0 && MODEL_VARS[k].type == type) return &MODEL_VARS[k];
    }
    for (int k = 0; k < MODEL_N_VARS; ++k)
        if (MODEL_VARS[k].vr == vr && MODEL_VARS[k].type == type) return &MODEL_VARS[k];
    logf_(c, fmi2Error, "%s: no %s variable has value reference %u", fn,
          type == 'R' ? "Real" : type == 'I' ? "Integer" : "Boolean", (unsigned)vr);
    return NULL;
}

static fmi2Status get_values(fmi2Component component, const char *fn, char type,
                             const fmi2ValueReference vr[], size_t nvr, double *real, int *integer)
{
    Inst *c = (Inst *)component;
    if (!c) return fmi2Error;
    if (!allowed(c, fn, P_ANY & ~P_INST)) return fmi2Error;
    if (nvr > 0 && (!vr || (!real && !integer))) {
        logf_(c, fmi2Error, "%s: NULL array", fn);
        return fmi2Error;
    }
    for (size_t i = 0; i < nvr; ++i) {
        const ModelVar *v = find(c, fn, vr[i], type);
        if (!v) return fmi2Error;
        double x = *slot_of(c, v);
        if (real) real[i] = x;
        else integer[i] = type == 'B' ? x != 0.0 : (int)x;
    }
    return fmi2OK;
}

static fmi2Status set_values(fmi2Component component, const char *fn, char type,
                             const fmi2ValueReference vr[], size_t nvr, const double *real,
                             const int *integer)
{
    Inst *c = (Inst *)component;
    if (!c) return fmi2Error;
    if (!allowed(c, fn, P_INST | P_INIT | P_OK)) return fmi2Error;
    if (nvr > 0 && (!vr || (!real && !integer))) {
        logf_(c, fmi2Error, "%s: NULL array", fn);
        return fmi2Error;
    }
    for (size_t i = 0; i < nvr; ++i) {   /* every one checked before any is written */
        const ModelVar *v = find(c, fn, vr[i], type);
        if (!v) return fmi2Error;
        if (v->array == IN_OUT) {
            logf_(c, fmi2Error, "%s: %s is an output", fn, v->name);
            return fmi2Error;
        }
        if (v->array == IN_T && c->phase == STEP_COMPLETE) {
            logf_(c, fmi2Error, "%s: %s is a fixed parameter: set it before initialisation",
                  fn, v->name);
            return fmi2Error;
        }
    }
    for (size_t i = 0; i < nvr; ++i)
        *slot_of(c, find(c, fn, vr[i], type)) =
            real ? real[i] : type == 'B' ? (double)(integer[i] != 0) : (double)integer[i];
    return fmi2OK;
}

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Real value[])
{
    return get_values(c, "fmi2GetReal", 'R', vr, nvr, value, NULL);
}

fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Integer value[])
{
    return get_values(c, "fmi2GetInteger", 'I', vr, nvr, NULL, value);
}

fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Boolean value[])
{
    return get_values(c, "fmi2GetBoolean", 'B', vr, nvr, NULL, (int *)value);
}

fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2String value[])
{
    (void)value;
    return get_values(c, "fmi2GetString", 'S', vr, nvr, NULL, NULL);
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Real value[])
{
    return set_values(c, "fmi2SetReal", 'R', vr, nvr, value, NULL);
}

fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Integer value[])
{
    return set_values(c, "fmi2SetInteger", 'I', vr, nvr, NULL, value);
}

fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Boolean value[])
{
    return set_values(c, "fmi2SetBoolean", 'B', vr, nvr, NULL, (const int *)value);
}

fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2String value[])
{
    (void)value;
    return set_values(c, "fmi2SetString", 'S', vr, nvr, NULL, NULL);
}

/* ---- the step ----------------------------------------------------------------------------- */

static fmi2Status discard(Inst *c, double t)
{
    c->phase = STEP_FAILED;
    c->last_ok_time = t;
    c->wants_to_terminate = 1;
    return fmi2Discard;
}

fmi2Status fmi2DoStep(fmi2Component component, fmi2Real t, fmi2Real h,
                      fmi2Boolean noSetFMUStatePriorToCurrentPoint)
{
    (void)noSetFMUStatePriorToCurrentPoint;
    Inst *c = (Inst *)component;
    if (!c) return fmi2Error;
    if (!allowed(c, "fmi2DoStep", P_OK)) return fmi2Error;
    if (!(h > 0.0) || !isfinite(h) || !isfinite(t)) {
        logf_(c, fmi2Error, "fmi2DoStep: communicationStepSize = %g at t = %g: must be finite "
              "and > 0", h, t);
        return fmi2Error;
    }
    char why[512];
    for (int k = 0; k < MODEL_N_VARS; ++k) {      /* the inputs a master set */
        const ModelVar *v = &MODEL_VARS[k];
        if (v->array == IN_IN && !native_value_ok(v, *slot_of(c, v), why, sizeof why)) {
            logf_(c, fmi2Error, "invalid input at t = %g s: %s", t, why);
            return discard(c, t);
        }
    }
    c->arr[A_TH][0] = t;
    c->arr[A_TH][1] = h;
    int units = (int)model_step_units(c->arr);   /* (a joint's needle-resolved rollers) */
    int32_t rc = units > 1 ? native_step_units(c->arr, units) : model_step(c->arr);
    if (MODEL_NOTES_AT >= 0 && c->arr[A_W][MODEL_NOTES_AT] != 0.0) {   /* (worded only then) */
        char prefix[96];
        snprintf(prefix, sizeof prefix, "step refused at t = %g s: ", t);
        log_notes(c, prefix);
    }
    if (rc == 5) {     /* an input the model derived (driving by angle: omega) */
        for (int k = 0; k < MODEL_N_VARS; ++k) {
            const ModelVar *v = &MODEL_VARS[k];
            if (v->array == IN_IN && !native_value_ok(v, *slot_of(c, v), why, sizeof why)) {
                logf_(c, fmi2Error, "invalid input at t = %g s: %s", t, why);
                break;
            }
        }
        return discard(c, t);
    }
    if (rc != 1) {
        if (rc != 3)
            logf_(c, fmi2Error, rc == 2 ? "non-finite output at t = %g s; step rejected" :
                  "the compiled step stopped on an arithmetic error at t = %g s", t);
        return discard(c, t);
    }
    c->last_ok_time = t + h;
    return fmi2OK;
}

fmi2Status fmi2CancelStep(fmi2Component c)
{
    logf_((Inst *)c, fmi2Error, "fmi2CancelStep: the steps are not asynchronous");
    return fmi2Error;
}

/* ---- FMU state ---------------------------------------------------------------------------- */

static State *new_state(Inst *c)
{
    State *s = calloc(1, sizeof *s);
    if (s) s->data = malloc(c->n_state * sizeof *s->data);
    if (s && !s->data) {
        free(s);
        s = NULL;
    }
    if (s) s->n_data = c->n_state;
    return s;
}

static void take(Inst *c, State *s)
{
    memcpy(s->data, c->data, c->n_state * sizeof *c->data);
    s->phase = c->phase;
    s->last_ok_time = c->last_ok_time;
    s->wants_to_terminate = c->wants_to_terminate;
}

fmi2Status fmi2GetFMUstate(fmi2Component component, fmi2FMUstate *FMUstate)
{
    Inst *c = (Inst *)component;
    if (!c) return fmi2Error;
    if (!FMUstate) {
        logf_(c, fmi2Error, "fmi2GetFMUstate: NULL pointer");
        return fmi2Error;
    }
    State *s = *FMUstate ? (State *)*FMUstate : new_state(c);   /* given back: overwritten */
    if (!s || s->n_data != c->n_state) {
        logf_(c, fmi2Error, "fmi2GetFMUstate: out of memory or a state of another FMU");
        return fmi2Error;
    }
    take(c, s);
    *FMUstate = s;
    return fmi2OK;
}

/* The work W a stepping state's parameters need (the needle rows' geometry, caches keyed on
   the parameters), built by the model's own start on a scratch copy of the state, whose
   checks are initialisation's (the relations between parameters; the model's notes are then
   the reason, logged).  0 when refused; why is empty when the notes said it. */
static int work_for(Inst *c, const State *s, double *scratch, char *why, size_t n)
{
    memcpy(scratch, s->data, c->n_state * sizeof *scratch);
    memset(scratch + c->n_state, 0, (c->n_data - c->n_state) * sizeof *scratch);
    double *arr[A_COUNT];
    place_arrays(arr, scratch);
    int32_t rc = model_init(arr);
    if (rc == 1) return 1;
    why[0] = '\0';
    if (rc == 3) {
        log_notes_of(c, arr[A_W], "fmi2SetFMUstate: invalid parameter in the state: ");
    } else if (rc < 0) {
        for (int k = 0; k < MODEL_N_VARS; ++k) {
            const ModelVar *v = &MODEL_VARS[k];
            if (v->array != IN_T || v->slot != -rc - 1) continue;
            char text[48];
            native_value_text(v, arr[A_T][v->slot], text, sizeof text);
            snprintf(why, n, "invalid parameter in the state: %s = %s is too small to compute "
                     "with; allowed range %s", v->name, text, v->range_text);
        }
    } else {
        snprintf(why, n, "invalid parameters in the state: their start's outputs are not finite");
    }
    if (!why[0] && rc != 3) snprintf(why, n, "invalid parameters in the state");
    return 0;
}

/* Whether the state's values can be set into this instance: finite; its inputs and parameters
   in range (FMI 2.0 counts the parameters part of the state: they come with it); a stepping
   state's parameters accepted by the model's start and its arrays by the model's own check.
   *scratch: a block holding the work built for the state's parameters (this instance's W is for
   other parameters, or for none yet), the caller's to free; NULL where this instance's serves
   (a rollback: nothing allocated). */
static int state_fits(Inst *c, const State *s, double **scratch, char *why, size_t n)
{
    *scratch = NULL;
    if (s->n_data != c->n_state) {
        snprintf(why, n, "a state of another model");
        return 0;
    }
    for (size_t i = 0; i < s->n_data; ++i)
        if (!isfinite(s->data[i])) {
            snprintf(why, n, "the state cannot be stepped: it holds a non-finite value");
            return 0;
        }
    int same = 1;
    for (int k = 0; k < MODEL_N_VARS; ++k) {
        const ModelVar *v = &MODEL_VARS[k];
        size_t at = (size_t)(slot_of(c, v) - c->data);
        double x = s->data[at];
        if (v->array == IN_IN && !native_value_ok(v, x, why, n)) return 0;
        if (v->array != IN_T) continue;
        if (!native_value_ok(v, x, why, n)) {
            char text[512];
            snprintf(text, sizeof text, "invalid parameter in the state: %s", why);
            snprintf(why, n, "%s", text);
            return 0;
        }
        if ((v->type == 'I' || v->type == 'B') && (x != floor(x) || (v->type == 'B' && x != 0.0
                                                                     && x != 1.0))) {
            snprintf(why, n, "invalid parameter in the state: %s = %.17g is not %s", v->name, x,
                     v->type == 'I' ? "an integer" : "a Boolean (0 or 1)");
            return 0;
        }
        same = same && x == c->data[at];
    }
    if (!(s->phase >= INSTANTIATED && s->phase <= ERRORED) || !isfinite(s->last_ok_time)) {
        snprintf(why, n, "corrupt state: its phase or time");
        return 0;
    }
    if (s->phase == STEP_COMPLETE || s->phase == STEP_FAILED || s->phase == TERMINATED) {
        int built = same && (c->phase == STEP_COMPLETE || c->phase == STEP_FAILED ||
                             c->phase == TERMINATED);
        if (!built) {
            *scratch = malloc(c->n_data * sizeof **scratch);
            if (!*scratch) {
                snprintf(why, n, "out of memory");
                return 0;
            }
            if (!work_for(c, s, *scratch, why, n)) return 0;
        }
        double *arr[A_COUNT];     /* the model's own check of what it would step (its work:
                                     the state's parameters') */
        place_arrays(arr, s->data);
        arr[A_W] = built ? c->arr[A_W] : *scratch + c->n_state;
        int32_t code = model_check_state(arr);
        if (code != 0) {
            snprintf(why, n, "corrupt state: %s",
                     code > 0 && code < MODEL_N_STATE_PROBLEMS ? MODEL_STATE_PROBLEMS[code]
                                                               : "refused by the model");
            return 0;
        }
    }
    return 1;
}

fmi2Status fmi2SetFMUstate(fmi2Component component, fmi2FMUstate FMUstate)
{
    Inst *c = (Inst *)component;
    if (!c) return fmi2Error;
    State *s = (State *)FMUstate;
    char why[512];
    if (!s) {
        logf_(c, fmi2Error, "fmi2SetFMUstate: NULL state");
        return fmi2Error;
    }
    double *scratch = NULL;
    if (!state_fits(c, s, &scratch, why, sizeof why)) {
        if (why[0]) logf_(c, fmi2Error, "fmi2SetFMUstate: %s", why);
        free(scratch);
        return fmi2Error;    /* the instance as it was, its phase included */
    }
    memcpy(c->data, s->data, c->n_state * sizeof *c->data);
    if (scratch)
        memcpy(c->data + c->n_state, scratch + c->n_state,
               (c->n_data - c->n_state) * sizeof *c->data);
    free(scratch);
    c->phase = s->phase;
    c->last_ok_time = s->last_ok_time;
    c->wants_to_terminate = s->wants_to_terminate;
    return fmi2OK;
}

fmi2Status fmi2FreeFMUstate(fmi2Component component, fmi2FMUstate *FMUstate)
{
    (void)component;
    if (FMUstate && *FMUstate) {
        State *s = (State *)*FMUstate;
        free(s->data);
        free(s);
        *FMUstate = NULL;
    }
    return fmi2OK;
}

static size_t serial_size(const State *s) { return native_state_size(s->n_data); }

fmi2Status fmi2SerializedFMUstateSize(fmi2Component component, fmi2FMUstate FMUstate, size_t *size)
{
    Inst *c = (Inst *)component;
    if (!c) return fmi2Error;
    if (!FMUstate || !size) {
        logf_(c, fmi2Error, "fmi2SerializedFMUstateSize: NULL pointer");
        return fmi2Error;
    }
    *size = serial_size((State *)FMUstate);
    return fmi2OK;
}

fmi2Status fmi2SerializeFMUstate(fmi2Component component, fmi2FMUstate FMUstate,
                                 fmi2Byte serializedState[], size_t size)
{
    Inst *c = (Inst *)component;
    if (!c) return fmi2Error;
    State *s = (State *)FMUstate;
    if (!s || !serializedState || size < serial_size(s)) {
        logf_(c, fmi2Error, "fmi2SerializeFMUstate: NULL pointer or a buffer of %zu bytes "
              "(needs %zu)", size, s ? serial_size(s) : 0);
        return fmi2Error;
    }
    native_state_write((unsigned char *)serializedState, (uint32_t)s->phase,
                       (uint32_t)s->wants_to_terminate, s->last_ok_time, s->data, s->n_data);
    return fmi2OK;
}

/* Every byte checked before it is used: the length this model's state has, the magic, the
   checksum, the version, this FMU's GUID, the model's sizes. */
fmi2Status fmi2DeSerializeFMUstate(fmi2Component component, const fmi2Byte serializedState[],
                                   size_t size, fmi2FMUstate *FMUstate)
{
    Inst *c = (Inst *)component;
    if (!c) return fmi2Error;
    const unsigned char *p = (const unsigned char *)serializedState;
    const char *why = !p || !FMUstate ? "NULL pointer" :
                      native_state_check(p, size, c->n_state, ERRORED);
    if (why) {
        logf_(c, fmi2Error, "fmi2DeSerializeFMUstate: %s", why);
        return fmi2Error;
    }
    State *s = *FMUstate ? (State *)*FMUstate : new_state(c);
    if (!s || s->n_data != c->n_state) {
        logf_(c, fmi2Error, "fmi2DeSerializeFMUstate: out of memory or a state of another FMU");
        return fmi2Error;
    }
    uint32_t phase, wants;
    native_state_read(p, &phase, &wants, &s->last_ok_time, s->data, s->n_data);
    s->phase = (Phase)phase;
    s->wants_to_terminate = (int)wants;
    *FMUstate = s;
    return fmi2OK;
}

/* ---- not provided, and the status inquiries ------------------------------------------------ */

static fmi2Status unsupported(fmi2Component c, const char *what)
{
    logf_((Inst *)c, fmi2Error, "%s is not provided (see the model description)", what);
    return fmi2Error;
}

fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference vUnknown_ref[],
                                        size_t nUnknown, const fmi2ValueReference vKnown_ref[],
                                        size_t nKnown, const fmi2Real dvKnown[],
                                        fmi2Real dvUnknown[])
{
    (void)vUnknown_ref, (void)nUnknown, (void)vKnown_ref, (void)nKnown, (void)dvKnown,
        (void)dvUnknown;
    return unsupported(c, "fmi2GetDirectionalDerivative");
}

fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                       const fmi2Integer order[], const fmi2Real value[])
{
    (void)vr, (void)nvr, (void)order, (void)value;
    return unsupported(c, "fmi2SetRealInputDerivatives");
}

fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                        const fmi2Integer order[], fmi2Real value[])
{
    (void)vr, (void)nvr, (void)order, (void)value;
    return unsupported(c, "fmi2GetRealOutputDerivatives");
}

fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind s, fmi2Status *value)
{
    (void)c, (void)s, (void)value;
    return fmi2Discard;     /* nothing pending: the steps are synchronous */
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

fmi2Status fmi2GetBooleanStatus(fmi2Component component, const fmi2StatusKind s,
                                fmi2Boolean *value)
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
