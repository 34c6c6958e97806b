"""The roller bordering the needle ring in one linear solve (the needle-resolved bearing's
coupled system): Schur complement on the roller's six unknowns over the ring's block chain
(ring.py).
"""

from .jit import inline, njit
from .layout import D_BORE
from .linalg import solve_small
from . import ring


@njit
def coupled_solve(A, b, NW, g, n, trav):
    """The roller (A y = b, its unknowns) bordering the needles' ring (R x = g FN) through
    the coupling blocks BN (needle rows, the roller's standard velocities; zero for a needle
    clear of the bore, ND[j, D_BORE] = 0): Schur complement on the roller.  b <- y, FN <- x.

    An open ring (some neighbours apart, the usual case): block Cholesky along the chain
    (needles.chain_forward), U = Z^T Z with Z = L^-1 B', one back substitution.  A closed ring,
    or a block that is not positive definite: R^-1 applied to g FN and the six coupling
    columns in one elimination (ring_solve_m, _coupled_solve_general)."""
    FN, AN, UN, RH, ZF = NW.FN, NW.AN, NW.UN, NW.RH, NW.ZF
    _coupled_rhs(NW, g, n, trav)
    j0 = -1
    for k in range(n):
        if not ring.touching(UN[k]):
            j0 = (k + 1) % n
            break
    if j0 < 0 or not ring.chain_forward(AN, UN, RH, ZF, n, j0, NW.LF, NW.CW):
        if j0 >= 0:
            _coupled_rhs(NW, g, n, trav)   # the failed sweep wrote over them
        _coupled_solve_general(A, b, NW, n)
        return
    U = NW.S   # Z^T Z is symmetric: its upper triangle, then both of A's
    for c in range(6):
        for d in range(6):
            U[c, d] = 0.0
    for j in range(n):
        if ZF[j] > 0.0:
            for i in range(6):
                y0 = RH[j, i, 0]
                for c in range(6):
                    zc = RH[j, i, 1 + c]
                    if zc != 0.0:
                        b[c] -= zc * y0
                        for d in range(c, 6):
                            U[c, d] += zc * RH[j, i, 1 + d]
    _schur_solve(A, b, U)
    ring.chain_backward(RH, ZF, b, UN, n, j0, NW.LF, NW.CW, FN)


@njit
def _coupled_rhs(NW, g, n, trav):
    """coupled_solve's right-hand sides RH[j] = (g FN[j], B'[j]) with B' = BN TM^T, zero for a
    needle clear of the bore; ZF[j] flags those on it."""
    FN, ND, BN, RH, ZF = NW.FN, NW.ND, NW.BN, NW.RH, NW.ZF
    TM = NW.RS[:, 7:13]
    # B' = BN TM^T: TM has 7 nonzeros of 36 (needles._roller_unknowns), listed once here
    nz = 0
    KC = NW.S   # scratch (6 x 6): row c lists TM[c]'s nonzero columns, -1 after the last
    for c in range(6):
        m = 0
        if trav or c > 0:
            for k in range(6):
                if TM[c, k] != 0.0:
                    KC[c, m] = k
                    m += 1
        if m < 6:
            KC[c, m] = -1.0
        nz += m
    for j in range(n):
        bore = ND[j, D_BORE] > 0.0 and nz > 0
        ZF[j] = 1.0 if bore else 0.0
        for i in range(6):
            RH[j, i, 0] = g * FN[j, i]
            for c in range(6):
                acc = 0.0
                if bore:
                    for m in range(6):
                        k = int(KC[c, m])
                        if k < 0:
                            break
                        acc += BN[j, i, k] * TM[c, k]
                RH[j, i, 1 + c] = acc


@inline
def _schur_solve(A, b, U):
    """y = (A - U)^-1 b in b, U symmetric (its upper triangle given)."""
    for c in range(6):
        A[c, c] -= U[c, c]
        for d in range(c + 1, 6):
            A[c, d] -= U[c, d]
            A[d, c] -= U[c, d]
    solve_small(A, b, 6)


@njit
def _coupled_solve_general(A, b, NW, n):
    """coupled_solve for any ring, its right-hand sides RH already set (g FN, then B'):
    R^-1 applied to all seven in one elimination (ring_solve_m), then the Schur complement."""
    FN, AN, UN, ND, RH, Bp = NW.FN, NW.AN, NW.UN, NW.ND, NW.RH, NW.BP
    for j in range(n):
        for i in range(6):
            for c in range(6):
                Bp[j, i, c] = RH[j, i, 1 + c]   # kept: the solve overwrites RH
    ring.ring_solve_m(AN, UN, RH, 7, n, NW.CW, NW.XW7, NW.S, NW.T7)
    U = NW.S   # B'^T R^-1 B' is symmetric: its upper triangle
    for c in range(6):
        for d in range(6):
            U[c, d] = 0.0
    for j in range(n):
        if ND[j, D_BORE] > 0.0:
            for c in range(6):
                for i in range(6):
                    bc = Bp[j, i, c]
                    if bc != 0.0:
                        b[c] -= bc * RH[j, i, 0]
                        for d in range(c, 6):
                            U[c, d] += bc * RH[j, i, 1 + d]
    _schur_solve(A, b, U)
    for j in range(n):
        for i in range(6):
            acc = RH[j, i, 0]
            for c in range(6):
                acc -= RH[j, i, 1 + c] * b[c]
            FN[j, i] = acc
