/* A variable's value against its range and in words (native_values.c). */
#ifndef NATIVE_VALUES_H
#define NATIVE_VALUES_H

#include <stddef.h>

#include "native_model.h"

/* x as check_param words variable v's value: a float's repr, an integer's digits */
void native_value_text(const ModelVar *v, double x, char *out, size_t n);
/* 1 when x is a value v may take; else 0 and the reason, "NAME = VALUE is ...", in why */
int native_value_ok(const ModelVar *v, double x, char *why, size_t n);

#endif
