/* A value against its variable's range, worded as reduced_model/scene.py's check_param words
   it (a float as Python's repr writes it), so the compiled FMU's messages are the Python
   model's to the character.  Pure functions over native_model.h's ModelVar. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "native_values.h"

/* x as Python's repr() writes a float (the shortest digits that read back as x; fixed notation
   for exponents -4 to 15, with ".0" when integral; else d.ddde+XX), so the messages are the
   Python model's to the character. */
static void py_repr(double x, char *out, size_t n)
{
    if (isnan(x)) { snprintf(out, n, "nan"); return; }
    if (isinf(x)) { snprintf(out, n, x < 0 ? "-inf" : "inf"); return; }
    char buf[40];
    int p;
    for (p = 1; p < 17; ++p) {
        snprintf(buf, sizeof buf, "%.*e", p - 1, x);
        if (strtod(buf, NULL) == x) break;
    }
    snprintf(buf, sizeof buf, "%.*e", p - 1, x);
    char digits[24];
    int nd = 0, neg = buf[0] == '-';
    const char *q = buf + neg;
    for (; *q && *q != 'e'; ++q)
        if (*q >= '0' && *q <= '9' && nd < 23) digits[nd++] = *q;
    digits[nd] = 0;
    int e = atoi(q + 1);
    while (nd > 1 && digits[nd - 1] == '0') digits[--nd] = 0;   /* (%.0e of 10: "1e+01") */
    char *o = out;
    size_t left = n;
#define PUT(...) do { int w_ = snprintf(o, left, __VA_ARGS__); if (w_ < 0 || (size_t)w_ >= left) return; o += w_; left -= (size_t)w_; } while (0)
    if (neg) PUT("-");
    if (e >= -4 && e < 16) {
        if (e < 0) {
            PUT("0.");
            for (int i = 0; i < -e - 1; ++i) PUT("0");
            PUT("%s", digits);
        } else {
            for (int i = 0; i <= e; ++i) PUT("%c", i < nd ? digits[i] : '0');
            PUT(".");
            if (nd > e + 1) PUT("%s", digits + e + 1);
            else PUT("0");
        }
    } else {
        PUT("%c", digits[0]);
        if (nd > 1) PUT(".%s", digits + 1);
        PUT("e%c%02d", e < 0 ? '-' : '+', e < 0 ? -e : e);
    }
#undef PUT
}

/* The value of variable k as check_param words it: a float's repr, an integer's digits. */
void native_value_text(const ModelVar *v, double x, char *out, size_t n)
{
    if (v->type == 'I') snprintf(out, n, "%.0f", x);
    else py_repr(x, out, n);
}

/* Whether x is a value variable v may take (reduced_model/scene.py: check_param); if not, the
   reason, "NAME = VALUE is ...", in why. */
int native_value_ok(const ModelVar *v, double x, char *why, size_t n)
{
    int bad = !isfinite(x);
    if (!bad && v->has_lo) bad = v->lo_open ? x <= v->lo : x < v->lo;
    if (!bad && v->has_hi) bad = v->hi_open ? x >= v->hi : x > v->hi;
    if (!bad && v->auto_or_min > 0.0) bad = 0.0 < x && x < v->auto_or_min;
    int subnormal = !bad && x != 0.0 && fabs(x) < DBL_MIN;
    if (!bad && !subnormal) return 1;
    char text[48];     /* (worded only when refused: a float's repr costs microseconds) */
    native_value_text(v, x, text, sizeof text);
    if (subnormal)
        snprintf(why, n, "%s = %s is subnormal (below %.4g in magnitude): give 0 or a value in %s",
                 v->name, text, DBL_MIN, v->range_text);
    else
        snprintf(why, n, "%s = %s is outside the allowed range %s", v->name, text,
                 v->range_text);
    return 0;
}

