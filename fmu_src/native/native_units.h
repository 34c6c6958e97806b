/* A model's step with its units (a joint's needle-resolved rollers) run at once (native_units.c). */
#ifndef NATIVE_UNITS_H
#define NATIVE_UNITS_H

#include <stdint.h>

/* model_step(args) of a model whose step has n > 1 units (model_step_units), the units
   stepped at once on up to as many threads as the machine has cores (each joined before it
   returns): the same bits as one after the other */
int32_t native_step_units(double **args, int n);

#endif
