/* The analytic FMU's communication step in C, for the native layer's fast path (issue 13: the
   analytic FMU near the bare FMI boundary).  What TripodRollerAnalytic._advance does at
   unchanged inputs: every roller's whirl angle advances by omega h, and the outputs follow from
   the traverse model's periodic table (reduced_model/traverse.py, Traverse.at: linear
   interpolation) or from Eqs. (18)-(27) (reduced_model/thrust.py, Thrust.at).  The same
   operations in the same order as that Python, so both paths give the same bits
   (tests/test_fast.py); compiled with -ffp-contract=off for that.

   The slave fills OP by the names tripod_analytic_layout() gives, so this file is the one
   place the layout is written. */
#include <math.h>
#include <stdint.h>

enum { W, N_ROLLERS, F, TABLE, SCALE, N, A, B, MU_F, K, TH, K_SPIN, OP_LEN };
enum { FX, FY, FZ, FZ_MOD, DFX, SLIP, FZ_JOINT, FZ_2, FZ_3, OUT_LEN };

/* "OP names | output names", each list in its array's order */
const char *tripod_analytic_layout(void)
{
    return "w n_rollers F table scale n A B muF k th kspin"
           "|Fx Fy Fz Fz_mod dFx slip_speed Fz_joint Fz_2 Fz_3";
}

/* Python's x % 2 pi (the sign of the divisor) */
static double wrap(double x)
{
    const double p = 6.283185307179586;
    double m = fmod(x, p);
    if (m != 0.0) {
        if ((m < 0.0) != (p < 0.0)) m += p;
    } else {
        m = copysign(0.0, p);
    }
    return m;
}

/* X: whirl angles [rad] (advanced in place), T: the table's rows (Fz, Fz_mod, Fx, Fy, slip
   speed) at n + 1 equally spaced angles over a cycle, OP: the operating point (above), OUT: the
   outputs (N, m/s).  1: outputs written; 2: a non-finite output (nothing written); 3: a bad roller count. */
int32_t tripod_analytic_step(double *X, double *T, double *OP, double *OUT, double *u4,
                             double *u5, double *u6, double *u7, double *u8, double *u9,
                             double *u10, double *u11, double *u12, double *u13)
{
    (void)u4; (void)u5; (void)u6; (void)u7; (void)u8; (void)u9; (void)u10; (void)u11;
    (void)u12; (void)u13;
    int nr = (int)OP[N_ROLLERS];
    double fz[3] = {0.0, 0.0, 0.0}, o[OUT_LEN];
    if (nr < 1 || nr > 3) return 3;                   /* the slave offers 1 to 3 rollers */
    for (int i = 0; i < nr; ++i) X[i] += OP[W];
    if (OP[TABLE] != 0.0) {                           /* Traverse.at */
        long n = (long)OP[N];
        for (int i = 0; i < nr; ++i) {
            double u = wrap(X[i]) * OP[SCALE];
            long j = (long)u;
            if (j >= n) j = n - 1;
            double f = u - (double)j, r[5];
            const double *a = T + 5 * j, *b = a + 5;
            for (int q = 0; q < 5; ++q) r[q] = a[q] + f * (b[q] - a[q]);
            if (i == 0) {
                o[FZ] = r[0];
                o[FZ_MOD] = r[1];
                o[FX] = r[2];
                o[FY] = r[3];
                o[SLIP] = r[4];
            }
            fz[i] = r[0];
        }
        o[DFX] = o[FX] - OP[F];
    } else {                                           /* Thrust.at, Eqs. (18)-(27) */
        for (int i = 0; i < nr; ++i) {
            double x = X[i], sx = sin(x);
            double V = OP[A] * sin(2.0 * x) + OP[B] * cos(2.0 * x);
            double ft = OP[MU_F] * tanh(OP[K] * V);
            double phi = OP[TH] * sx;
            double ftz = ft * sin(phi);
            fz[i] = ftz + OP[K_SPIN] * sx;
            if (i == 0) {
                o[FZ] = fz[0];
                o[FY] = ft * cos(phi);
                o[FX] = OP[F];
                o[DFX] = 0.0;
                o[FZ_MOD] = o[FZ];
                o[SLIP] = fabs(V);
            }
        }
    }
    o[FZ_JOINT] = fz[0] + fz[1] + fz[2];
    o[FZ_2] = fz[1];
    o[FZ_3] = fz[2];
    for (int q = 0; q < OUT_LEN; ++q)
        if (!isfinite(o[q])) return 2;
    for (int q = 0; q < OUT_LEN; ++q) OUT[q] = o[q];
    return 1;
}
