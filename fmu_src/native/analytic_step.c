/* The analytic FMU's communication step in C, for the native layer's fast path (the analytic
   FMU near the bare FMI boundary).  What AnalyticModel.step and .outputs
   (reduced_model/analytic_model.py) do at unchanged inputs: every roller's whirl angle advances by omega h, and the outputs follow from
   the traverse model's periodic table (reduced_model/traverse.py, Traverse.at: linear
   interpolation) or from Eqs. (18)-(27) (reduced_model/thrust.py, Thrust.at).  The same
   operations in the same order as that Python, so both paths give the same bits
   (tests/test_fast.py); compiled with -ffp-contract=off for that.

   Once a master moves the inputs, tripod_analytic_march steps the roller's slide in time at
   each step's inputs, as reduced_model/traverse.py's Traverse.march does (T2-T6 of its header,
   _slip_step first and _step where that does not settle:
   the same operations in the same order, libm's scalar functions as Python's math module), and
   derives the operating point from the inputs the native layer wrote (AnalyticModel.prepare,
   Traverse.__init__).

   The slave fills OP by the names tripod_analytic_layout() gives, so this file is the one
   place the layout is written. */
#include <float.h>
#include <math.h>
#include <stdint.h>

#define PI 3.141592653589793   /* math.pi */
#define V_ST_FLOOR 1e-6        /* reduced_model/friction.py: V_ST_FLOOR [m/s] */
#define MAX_SUBSTEPS 1048576.0 /* reduced_model/scene.py: MAX_SUBSTEPS, a step's most substeps */

enum { OMEGA, N_ROLLERS, F, TABLE, SCALE, N, A, B, MU_F, K, TH, K_SPIN, S_PITCH, VP, PLUNGE_SPEED, DT,
       OP_LEN };
enum { FX, FY, FZ, FZ_MOD, DFX, SLIP, FZ_JOINT, FZ_2, FZ_3, WHIRL, FX_2, FY_2, FX_3, FY_3,
       F_HOUSING_X, F_HOUSING_Y, T_HOUSING, F_ROLLER, PLUNGE, OUT_LEN };
#define N_IN 5   /* the march's inputs: theta, omega, F_press, torque, plunge speed */

/* the march's operating point (tripod_analytic_march): the inputs where the native layer
   writes a master's new values, the inputs the operating point was derived for (key), the step,
   and the scene's constants */
enum { M_THETA, M_OMEGA, M_F_PRESS, M_TORQUE, M_PLUNGE, M_KEY_THETA, M_KEY_OMEGA,
       M_KEY_F_PRESS, M_KEY_TORQUE, M_KEY_PLUNGE, M_DT, M_N_ROLLERS, M_N, M_MU, M_V_ST, M_K, M_A1, M_CLEAR, M_R, M_S, M_I,
       M_PITCH, M_ROLL, M_SPIN_MOMENT, M_THETA_LO, M_THETA_HI, M_OMEGA_LO, M_OMEGA_HI, M_LOAD_LO,
       M_LOAD_HI, MOP_LEN };
enum { S_S, S_P, S_FZ, S_FZ_MOD, S_FX, S_FY, S_SLIP, S_LEN };   /* march state per roller */

/* "OP names | output names | march OP names | march state names", each in its array's order */
const char *tripod_analytic_layout(void)
{
    return "omega n_rollers F table scale n A B muF k th kspin s vp plunge_speed dt"
           "|Fx Fy Fz Fz_mod dFx slip_speed Fz_joint Fz_2 Fz_3 whirl_angle"
           " Fx_2 Fy_2 Fx_3 Fy_3 F_housing_x F_housing_y T_housing F_roller plunge"
           "|theta omega F_press torque plunge_speed key_theta key_omega key_F_press key_torque"
           " key_plunge_speed dt n_rollers"
           " n mu v_st K a1 clear r s I pitch roll spin_moment"
           " theta_lo theta_hi omega_lo omega_hi load_lo load_hi"
           "|s p Fz Fz_mod Fx Fy slip";
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

/* The joint on the housing: reduced_model/housing.py's housing_forces, the same sums in the
   same order (rollers not simulated pass zeros), and the other rollers' forces. */
static void housing_into(double *o, const double fx[3], const double fy[3], double radius,
                         double F)
{
    static const double C[3] = {1.0, -0.4999999999999998, -0.5000000000000004};
    static const double S[3] = {0.0, 0.8660254037844387, -0.8660254037844384};
    double X = 0.0, Y = 0.0, T = 0.0;
    for (int i = 0; i < 3; ++i) {
        X += fx[i] * S[i] + fy[i] * C[i];
        Y += -fx[i] * C[i] + fy[i] * S[i];
        T += radius * fx[i];
    }
    o[FX_2] = fx[1];
    o[FY_2] = fy[1];
    o[FX_3] = fx[2];
    o[FY_3] = fy[2];
    o[F_HOUSING_X] = X;
    o[F_HOUSING_Y] = Y;
    o[T_HOUSING] = T;
    o[F_ROLLER] = F;
}

/* X: whirl angles [rad] (advanced in place), T: the table's rows (Fz, Fz_mod, Fx, Fy, slip
   speed) at n + 1 equally spaced angles over a cycle, OP: the operating point (above), OUT: the
   outputs (N, m/s).  1: outputs written; 2: a non-finite output (nothing written); 3: a bad roller count. */
int32_t tripod_analytic_step(double **args)
{
    double *X = args[0], *T = args[1], *OP = args[2], *OUT = args[3];
    int nr = (int)OP[N_ROLLERS];
    double fz[3] = {0.0, 0.0, 0.0}, fx[3] = {0.0, 0.0, 0.0}, fy[3] = {0.0, 0.0, 0.0}, o[OUT_LEN];
    if (nr < 1 || nr > 3) return 3;                   /* the slave offers 1 to 3 rollers */
    double w = OP[OMEGA] * OP[DT];                    /* AnalyticModel.step */
    for (int i = 0; i < nr; ++i) X[i] += w;
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
            fx[i] = r[2];
            fy[i] = r[3];
        }
        o[DFX] = o[FX] - OP[F];
    } else {                                           /* Thrust.at, Eqs. (18)-(27) */
        for (int i = 0; i < nr; ++i) {
            double x = X[i], sx = sin(x);
            double V = OP[A] * sin(2.0 * x) + OP[B] * cos(2.0 * x);
            double phi = OP[TH] * sx;
            if (OP[VP] != 0.0) V = V + OP[VP] * sin(phi);            /* plunging */
            double ft = OP[MU_F] * tanh(OP[K] * V);
            double ftz = ft * sin(phi);
            fz[i] = ftz + OP[K_SPIN] * sx;
            fx[i] = OP[F];
            fy[i] = ft * cos(phi);
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
    o[WHIRL] = X[0];
    o[PLUNGE] = OUT[PLUNGE] + OP[PLUNGE_SPEED] * OP[DT];
    housing_into(o, fx, fy, OP[S_PITCH], OP[F]);
    for (int q = 0; q < OUT_LEN; ++q)
        if (!isfinite(o[q])) return 2;
    for (int q = 0; q < OUT_LEN; ++q) OUT[q] = o[q];
    return 1;
}


/* ---- the march (Traverse.march) ------------------------------------------------------- */

typedef struct {
    double w, F, mu, vst, K, a1, clear, rho, r, s, I, T, k, vp;
    int held, sm, mirror;
} Op;

/* scene.same_value: a and b differ only by rounding (64 ulps of the larger) */
static int same_value(double a, double b)
{
    return fabs(a - b) <= 64.0 * DBL_EPSILON * fmax(fabs(a), fabs(b));
}

/* Python's min(a, b) and max(a, b) for floats: the first unless the second is smaller (larger) */
static double pmin(double a, double b) { return b < a ? b : a; }
static double pmax(double a, double b) { return b > a ? b : a; }

/* the operating point at the key's inputs (Traverse.__init__ with periodic=False).  Coast (a
   negative pressing load, scene.pressing_load) runs as drive at the opposite whirl and plunge
   speed turned about the trunnion axis (AnalyticModel.mirror, .inner): the inputs negated */
static void operating_point(const double *M, Op *o)
{
    double th = M[M_KEY_THETA], w = M[M_KEY_OMEGA], fp = M[M_KEY_F_PRESS], tq = M[M_KEY_TORQUE];
    double vp = M[M_KEY_PLUNGE];
    double F = tq != 0.0 ? tq / (3.0 * M[M_S]) : fp;                  /* scene.pressing_load */
    o->mirror = F < 0.0;
    if (o->mirror) {   /* (-tq) / (3 s) is -(tq / (3 s)) to the bit: the Python's inner scene */
        w = -w;
        vp = -vp;
        F = -F;
    }
    o->w = w;
    o->vp = vp;
    o->s = M[M_S];
    o->r = M[M_R];
    o->F = F;
    o->mu = M[M_MU];
    if (M[M_V_ST] > 0) {                                           /* thrust.transition_velocity */
        o->vst = M[M_V_ST];
    } else {
        double A = M[M_PITCH] != 0.0 ? 0.5 * o->s * w * pow(th, 2.0) : 0.0;   /* sliding.py */
        double B = 0.0;
        if (M[M_ROLL] != 0.0) {
            double c = cos(th);
            B = -o->r * w * (1.0 - c) / c;
        }
        double h = hypot(A, B);                                    /* friction.v_st_auto */
        double Vp = M[M_PITCH] != 0.0 ? fabs(o->vp) * sin(th) : 0.0; /* amplitude_plunge */
        if (Vp != 0.0) h = hypot(h, Vp);
        o->vst = pmax(h / 4.0, V_ST_FLOOR);
    }
    o->K = M[M_K];
    o->a1 = M[M_A1];
    o->clear = M[M_CLEAR];
    o->rho = o->F > 0 ? o->clear + pow(o->F / o->K, 2.0 / 3.0) : o->clear;
    o->I = M[M_I];
    o->sm = M[M_SPIN_MOMENT] != 0.0;
    o->held = o->F > 0 && o->mu > 0 && o->vst > 0;
    o->T = M[M_PITCH] != 0.0 ? tan(th) : 0.0;
    o->k = M[M_ROLL] != 0.0 ? (1.0 - cos(th)) / (2.0 * cos(th)) : 0.0;
}

typedef struct { double phi, xi, V, dphi, spin, bi; } Drive;

/* Traverse._drive_on at whirl angle x [rad] */
static void drive_on(const Op *o, double x, Drive *d)
{
    double T = o->T, k = o->k, w = o->w, r = o->r;
    double tz = T * sin(x);
    d->phi = atan(tz);
    d->dphi = T * w * cos(x) / (1.0 + tz * tz);
    double q = k * sin(2.0 * x);
    d->xi = asin(q);
    double dxi = 2.0 * w * k * cos(2.0 * x) / sqrt(1.0 - q * q);
    double zd = o->s * T * w * cos(x);
    if (o->vp != 0.0) zd = zd + o->vp;                              /* the plunge */
    double zdd = -o->s * T * w * w * sin(x);
    double v1 = zd * sin(d->phi);
    double v2 = -r * dxi;
    d->V = v1 + v2 * (1.0 + o->rho / r);
    d->spin = zd / r;
    d->bi = -o->I * zdd / (r * r);
}

/* T5: Traverse._fn */
static double normal_force(const Op *o, double p)
{
    double d = o->rho / sqrt(1.0 - p * p) - o->clear;
    return d > 0 ? o->K * pow(d, 1.5) : 0.0;
}

/* T2: Traverse._beta_at, with the spin moment of Eqs. (14)-(16) as
   reduced_model/friction.py: spin_moment */
static double beta_at(const Op *o, double p, double fn, const Drive *d)
{
    double b = d->bi;
    if (o->sm) {
        double a = o->a1 * pow(fn, 1.0 / 3.0);
        double wn = d->dphi + d->spin * p;
        double t = o->vst > 0 ? tanh(3.0 * wn * a / o->vst)
                              : (wn != 0 ? copysign(1.0, wn) : 0.0);
        b -= 0.375 * o->mu * t * fn * a * p / o->r;
    }
    return b / fn;
}

/* T3 inverted: Traverse._share */
static double share(const Op *o, double s, double B)
{
    double mu = o->mu, k = 3.0 / o->vst;
    B = pmin(B, mu * (1.0 - 1e-9));
    s = fabs(s);
    if (B <= 0.0) return mu * tanh(k * s);
    if (s == 0.0) return 0.0;
    double lo = 0.0, hi = 0.5 * PI;
    double a = pmin(asin(pmin(B / (mu * tanh(k * s) + 1e-300), 1.0)), 1.5);
    for (int it = 0; it < 60; ++it) {
        double c = cos(a), sn = sin(a);
        double th = tanh(k * s / c);
        double f = mu * th * sn - B;
        if (f > 0) hi = a;
        else lo = a;
        double df = mu * (th * c + sn * (1.0 - th * th) * k * s * sn / (c * c));
        double an = df > 0 ? a - f / df : 0.5 * (lo + hi);
        if (!(lo < an && an < hi)) an = 0.5 * (lo + hi);
        if (fabs(an - a) < 1e-10) {
            a = an;
            break;
        }
        a = an;
    }
    return mu * tanh(k * s / cos(a)) * cos(a);
}

/* T2, T3, T5: Traverse._p_at (p0: the guess, NAN for none) */
static double p_at(const Op *o, double s, const Drive *d, double p0)
{
    double sign = s > 0 ? -1.0 : 1.0;
    double p = sign * o->mu * tanh(3.0 * fabs(s) / o->vst);
    if (p0 == p0 && p0 * sign > 0.0) p = p0;
    for (int it = 0; it < 6; ++it) {
        double q = sign * share(o, s, fabs(beta_at(o, p, normal_force(o, p), d)));
        if (fabs(q - p) < 1e-11 * o->mu) return q;
        p = q;
    }
    return p;
}

/* T4, one trapezoidal step: Traverse._step with p0 (Newton kept in the root's bracket) */
static double trapezoid_step(const Op *o, double rhs0, double s, double h, const Drive *d,
                             double p0)
{
    double rho = o->rho, mu = o->mu;
    double e = 1e-6 * o->vst;
    double lo = -2.0 * (rho * mu + rhs0) / h, hi = 2.0 * (rho * mu - rhs0) / h;
    double z = pmin(pmax(s, lo), hi);
    for (int it = 0; it < 200; ++it) {
        double p1 = p_at(o, z, d, p0);
        p0 = p1;
        double res = rho * p1 - 0.5 * h * z - rhs0;
        if (res > 0.0) lo = z;
        else if (res < 0.0) hi = z;
        else break;
        double dd = (rho * (p_at(o, z + e, d, p1) - p1)) / e - 0.5 * h;
        double dz = -res / dd;
        if (!(lo < z + dz && z + dz < hi)) dz = 0.5 * (lo + hi) - z;
        z += dz;
        if (fabs(dz) < 1e-9 * o->vst) break;
    }
    return z;
}

/* T3 and T4 together, Newton on the slip vector: Traverse._slip_step (the march's first
   choice; 0 where it does not settle, and the caller takes trapezoid_step) */
static int slip_step(const Op *o, double rhs0, double s, double h, const Drive *d, double p0,
                     double *s1, double *p1)
{
    double rho = o->rho, mu = o->mu, k = 3.0 / o->vst;
    double kt = 0.5 * h;
    double cap = mu * (1.0 - 1e-9);
    double tol = 1e-9 * o->vst;
    double t = 0.0;
    if (p0 != 0.0)   /* the last step's slip angle */
        t = fabs(s * pmin(fabs(beta_at(o, p0, normal_force(o, p0), d)), cap) / p0);
    for (int it = 0; it < 30; ++it) {
        double v = sqrt(s * s + t * t);
        double gv = k, dg = k, us = 0.0, ut = 0.0;   /* the friction's slope at v = 0 */
        if (v > 0.0) {
            double g = tanh(k * v);
            gv = g / v;
            dg = k * (1.0 - g * g);
            us = s / v;
            ut = t / v;
        }
        double p = -mu * gv * s;
        double B = pmin(fabs(beta_at(o, p, normal_force(o, p), d)), cap);
        double a11 = mu * (gv * (1.0 - us * us) + dg * us * us);
        double a22 = mu * (gv * (1.0 - ut * ut) + dg * ut * ut);
        double a12 = mu * (dg - gv) * us * ut;
        double r1 = rho * p - kt * s - rhs0;
        double r2 = mu * gv * t - B;
        double j11 = -rho * a11 - kt;
        double j12 = -rho * a12;
        double det = j11 * a22 - j12 * a12;
        if (!(det < 0.0)) return 0;
        double ds = (j12 * r2 - a22 * r1) / det;
        double dt = (a12 * r1 - j11 * r2) / det;
        s += ds;
        t = fabs(t + dt);
        if (fabs(ds) < tol && fabs(dt) < tol) {
            v = sqrt(s * s + t * t);
            *s1 = s;
            *p1 = -mu * (v > 0.0 ? tanh(k * v) / v : k) * s;
            return 1;
        }
    }
    return 0;
}

/* X: whirl angles [rad] (advanced in place), S: per roller the march state (S_LEN: slide slip
   s [m/s], p [1], then its outputs Fz, Fz_mod, Fx, Fy [N], slip speed [m/s]), M: the march's
   operating point (above; the key is updated in place when the inputs moved beyond rounding),
   OUT: the outputs.  1: written; 2: a non-finite output (nothing written: X, S, M untouched);
   3: a bad roller count. */
int32_t tripod_analytic_march(double **args)
{
    double *X = args[0], *S = args[1], *M = args[2], *OUT = args[3];
    int nr = (int)M[M_N_ROLLERS];
    if (nr < 1 || nr > 3) return 3;
    double key[N_IN];
    int moved = 0;
    for (int q = 0; q < N_IN; ++q) moved |= !same_value(M[M_THETA + q], M[M_KEY_THETA + q]);
    for (int q = 0; q < N_IN; ++q) key[q] = moved ? M[M_THETA + q] : M[M_KEY_THETA + q];
    double saved[N_IN];
    for (int q = 0; q < N_IN; ++q) {
        saved[q] = M[M_KEY_THETA + q];
        M[M_KEY_THETA + q] = key[q];
    }
    Op o;
    operating_point(M, &o);
    /* the span of the inputs over the run (the slave compares it with where the traverse
       model was checked when the run ends) */
    M[M_THETA_LO] = fmin(M[M_THETA_LO], key[0]);
    M[M_THETA_HI] = fmax(M[M_THETA_HI], key[0]);
    M[M_OMEGA_LO] = fmin(M[M_OMEGA_LO], fabs(o.w));
    M[M_OMEGA_HI] = fmax(M[M_OMEGA_HI], fabs(o.w));
    M[M_LOAD_LO] = fmin(M[M_LOAD_LO], fabs(o.F));
    M[M_LOAD_HI] = fmax(M[M_LOAD_HI], fabs(o.F));
    double dt = M[M_DT], table_n = M[M_N];
    double nd = fabs(o.w) * dt * table_n / (2.0 * PI) - 1e-9;
    if (!(nd <= MAX_SUBSTEPS)) return 4;    /* refused before it starts (Traverse.march) */
    nd = ceil(nd);
    long n = nd > 1.0 ? (long)nd : 1;
    double h = dt / (double)n, wh = o.w * h;
    double x1[3], st[3][S_LEN], o_[OUT_LEN], fz[3] = {0.0, 0.0, 0.0};
    double fx[3] = {0.0, 0.0, 0.0}, fy[3] = {0.0, 0.0, 0.0};
    /* AnalyticModel.at, .outer: coast's whirl angle and forces turned about the trunnion axis */
    double turn = o.mirror ? -1.0 : 1.0;
    for (int i = 0; i < nr; ++i) {
        double x = o.mirror ? -X[i] : X[i], s = S[S_LEN * i + S_S], p = S[S_LEN * i + S_P];
        Drive d0, d1;
        drive_on(&o, x, &d0);
        for (long j = 0; j < n; ++j) {
            drive_on(&o, x + wh * (double)(j + 1), &d1);
            if (o.held) {
                double rhs0 = o.rho * p + 0.5 * h * (s - d0.V - d1.V);
                double s1, p1;
                if (slip_step(&o, rhs0, s, h, &d1, p, &s1, &p1)) {
                    s = s1;
                    p = p1;
                } else {
                    s = trapezoid_step(&o, rhs0, s, h, &d1, p);
                    p = p_at(&o, s, &d1, p);
                }
            }
            d0 = d1;
        }
        if (!o.held) {
            s = d0.V;
            p = 0.0;
        }
        double fn = o.F > 0 ? normal_force(&o, p) : 0.0;
        double beta = fn > 0 ? beta_at(&o, p, fn, &d0) : 0.0;
        /* T6: traverse.groove_forces */
        double Fz = -fn * (p * sin(d0.phi) + beta * cos(d0.phi));
        double Fx = fn * (sqrt(1.0 - p * p) + p * p - p * d0.xi);
        double Fy = -(Fx * sin(d0.xi) + Fz * cos(d0.xi) * sin(d0.phi)) / (cos(d0.xi) * cos(d0.phi));
        /* reduced_model/thrust.py: fz_mod */
        double Fz_mod = Fx * o.F > 1e-9 * pmax(o.F * o.F, 1.0) ? Fz * o.F / Fx : 0.0;
        x1[i] = x + wh * (double)n;
        if (o.mirror) x1[i] = -x1[i];
        st[i][S_S] = s;
        st[i][S_P] = p;
        st[i][S_FZ] = Fz;
        st[i][S_FZ_MOD] = Fz_mod;
        st[i][S_FX] = Fx;
        st[i][S_FY] = Fy;
        st[i][S_SLIP] = fabs(s);
        fz[i] = turn * Fz;
        fx[i] = turn * Fx;
        fy[i] = Fy;
    }
    /* AnalyticModel.outputs (the state rows keep the drive scene's forces, as its march) */
    double F_out = turn * o.F;
    o_[FZ] = fz[0];
    o_[FZ_MOD] = turn * st[0][S_FZ_MOD];
    o_[FX] = fx[0];
    o_[FY] = st[0][S_FY];
    o_[SLIP] = st[0][S_SLIP];
    o_[DFX] = o_[FX] - F_out;
    o_[FZ_JOINT] = fz[0] + fz[1] + fz[2];
    o_[FZ_2] = fz[1];
    o_[FZ_3] = fz[2];
    o_[WHIRL] = x1[0];
    o_[PLUNGE] = OUT[PLUNGE] + M[M_KEY_PLUNGE] * M[M_DT];
    housing_into(o_, fx, fy, o.s, F_out);
    int ok = 1;
    for (int q = 0; q < OUT_LEN; ++q) ok = ok && isfinite(o_[q]);
    for (int i = 0; i < nr; ++i)
        for (int q = 0; q < S_LEN; ++q) ok = ok && isfinite(st[i][q]);
    if (!ok) {
        for (int q = 0; q < N_IN; ++q) M[M_KEY_THETA + q] = saved[q];
        return 2;
    }
    for (int i = 0; i < nr; ++i) {
        X[i] = x1[i];
        for (int q = 0; q < S_LEN; ++q) S[S_LEN * i + q] = st[i][q];
    }
    for (int q = 0; q < OUT_LEN; ++q) OUT[q] = o_[q];
    return 1;
}
