"""The needle ring's linear solves (the needle-resolved bearing, needles.py): each needle a
6 x 6 block coupled to its two neighbours, an open chain (block Cholesky, chain_forward /
chain_backward) or a closed ring (ring_solve_m), for one right-hand side or several; and the
needles' own step once their velocities are solved (needle_update).
"""
import math

from .jit import inline, njit
from .layout import (N_F, N_I1, N_I3, N_MN, N_N)


@njit
def _solve6(A, B, nc):
    """A X = B for a 6 x 6 A and nc columns of B, in place (B <- X); partial pivoting."""
    for k in range(6):
        piv = k
        for i in range(k + 1, 6):
            if abs(A[i, k]) > abs(A[piv, k]):
                piv = i
        if piv != k:
            for j in range(6):
                A[k, j], A[piv, j] = A[piv, j], A[k, j]
            for j in range(nc):
                B[k, j], B[piv, j] = B[piv, j], B[k, j]
        inv = 1.0 / A[k, k]
        for i in range(k + 1, 6):
            f = A[i, k] * inv
            if f != 0.0:
                for j in range(k + 1, 6):
                    A[i, j] -= f * A[k, j]
                for j in range(nc):
                    B[i, j] -= f * B[k, j]
    for k in range(5, -1, -1):
        inv = 1.0 / A[k, k]
        for j in range(nc):
            acc = B[k, j]
            for i in range(k + 1, 6):
                acc -= A[k, i] * B[i, j]
            B[k, j] = acc * inv


@njit
def touching(U):
    """Whether a coupling block holds anything (the two needles touch or rub)."""
    for i in range(6):
        for l in range(6):
            if U[i, l] != 0.0:
                return True
    return False


@njit
def ring_solve(AN, UN, FN, h, n, CW, XW, S, T):
    """Solve the needles' coupled implicit system in place: block j has diagonal AN[j] (mass
    included), coupling UN[j] to block j+1 (mod n, the ring closes) and UN[j-1]^T to block
    j-1, right-hand side h FN[j]; the velocity increments replace FN.  CW (n x 6 x 6),
    XW (n x 6 x 7), S (6 x 6), T (6 x 13) are work arrays (ring_solve_m with one column)."""
    for j in range(n):
        for i in range(6):
            FN[j, i] *= h
    # (FN seen with one column: a view by indexing, as reshape needs a helper of numba's
    # runtime that the FMU's binary does not carry)
    ring_solve_m(AN, UN, FN[:, :, None], 1, n, CW, XW, S, T)


@njit
def needle_update(Y, y0, NW, h):
    """Linearly implicit step of every needle's velocities and positions (in Y from y0) from
    needle_forces' system: (M + h D + h^2 K) dv = h (F - h K v) over the whole ring
    (ring_solve); positions move with the new velocities (tilts: t1' = w2, t2' = -w1)."""
    NP, FN, AN, UN = NW.NP, NW.FN, NW.AN, NW.UN
    n = int(NP[N_N])
    mn, I1, I3 = NP[N_MN], NP[N_I1], NP[N_I3]
    for j in range(n):
        AN[j, 0, 0] += mn
        AN[j, 1, 1] += mn
        AN[j, 2, 2] += mn
        AN[j, 3, 3] += I1
        AN[j, 4, 4] += I1
        AN[j, 5, 5] += I3
    ring_solve(AN, UN, FN, h, n, NW.CW, NW.XW, NW.S, NW.T)
    for j in range(n):
        q = y0 + N_F * j
        for i in range(6):
            Y[q + 5 + i] += FN[j, i]
        Y[q] += h * Y[q + 5]
        Y[q + 1] += h * Y[q + 6]
        Y[q + 2] += h * Y[q + 7]
        Y[q + 3] += h * Y[q + 9]
        Y[q + 4] -= h * Y[q + 8]


@njit
def ring_solve_m(AN, UN, RHS, nr, n, CW, XW, S, T):
    """The ring's system (ring_solve) for nr right-hand sides at once (RHS[j, :, c],
    n x 6 x nr, replaced by the solutions): one elimination for all of them.

    Where two neighbours do not touch the ring is open: then a chain from the needle after that
    gap (_chain_solve_m).  A closed ring (every needle touching the next): block tridiagonal
    elimination bordered by the block that closes it (_closed_ring_solve_m).
    CW (n x 6 x 6), XW (n x 6 x (nr + 6)), S (6 x 6), T (6 x (nr + 12)) are work arrays.
    """
    for k in range(n):
        if not touching(UN[k]):
            _chain_solve_m(AN, UN, RHS, nr, n, (k + 1) % n, CW, XW, S, T)
            return
    _closed_ring_solve_m(AN, UN, RHS, nr, n, CW, XW, S, T)


@njit
def _chain_solve_m(AN, UN, RHS, nr, n, j0, CW, XW, S, T):
    """The ring opened before needle j0 (UN[j0 - 1] = 0): block tridiagonal elimination along
    j0, j0 + 1, ... (mod n); a gap further on leaves its coupling column out (C_j = 0).  T's
    columns 0..nr-1 the right-hand sides, nr..nr+5 the coupling to the next needle.  About
    600 multiply-adds a touching needle and right-hand side, 150 a free one."""
    prev = -1   # the previous needle of the chain when it touches this one
    for m in range(n):
        j = (j0 + m) % n
        for i in range(6):
            for l in range(6):
                S[i, l] = AN[j, i, l]
            for c in range(nr):
                T[i, c] = RHS[j, i, c]
        if prev >= 0:   # subtract L C_prev and L X_prev, L = UN[prev]^T
            for i in range(6):
                for q in range(6):
                    lim = UN[prev, q, i]
                    if lim != 0.0:
                        for l in range(6):
                            S[i, l] -= lim * CW[prev, q, l]
                        for c in range(nr):
                            T[i, c] -= lim * XW[prev, q, c]
        nxt = m < n - 1 and touching(UN[j])
        if nxt:
            for i in range(6):
                for l in range(6):
                    T[i, nr + l] = UN[j, i, l]
            _solve6(S, T, nr + 6)
        else:
            _solve6(S, T, nr)
        for i in range(6):
            for l in range(6):
                CW[j, i, l] = T[i, nr + l] if nxt else 0.0
            for c in range(nr):
                XW[j, i, c] = T[i, c]
        prev = j if nxt else -1
    # back substitution: x_j = X_j - C_j x_next (C_j = 0 at a gap, and after the chain's end)
    for m in range(n - 1, -1, -1):
        j = (j0 + m) % n
        jn = (j + 1) % n
        for c in range(nr):
            for i in range(6):
                acc = XW[j, i, c]
                if m < n - 1:
                    for l in range(6):
                        acc -= CW[j, i, l] * RHS[jn, l, c]
                RHS[j, i, c] = acc


@njit
def _closed_ring_solve_m(AN, UN, RHS, nr, n, CW, XW, S, T):
    """Every needle touches the next: block tridiagonal elimination on blocks 0..n-2 bordered
    by block n-1 (which closes the ring): x_j = y_j - Z_j x_{n-1}, then the border's 6 x 6
    system.  T's columns 0..5 the coupling C_k, 6..5+nr the right-hand sides, 6+nr..11+nr the
    border; XW[k] holds the right-hand sides' and the border's columns (nr + 6)."""
    M = n - 1
    nb = nr + 6
    for k in range(M):
        for i in range(6):
            for l in range(6):
                S[i, l] = AN[k, i, l]
            for l in range(6 + nb):
                T[i, l] = 0.0
            if k < M - 1:
                for l in range(6):
                    T[i, l] = UN[k, i, l]
            for c in range(nr):
                T[i, 6 + c] = RHS[k, i, c]
            if k == 0:                       # A[0][n-1] = UN[n-1]^T
                for l in range(6):
                    T[i, 6 + nr + l] += UN[n - 1, l, i]
            if k == M - 1:                   # A[n-2][n-1] = UN[n-2]
                for l in range(6):
                    T[i, 6 + nr + l] += UN[M - 1, i, l]
        if k > 0:   # subtract L_k C_{k-1} and L_k X_{k-1}, L_k = UN[k-1]^T
            for i in range(6):
                for m in range(6):
                    lim = UN[k - 1, m, i]
                    if lim != 0.0:
                        for l in range(6):
                            S[i, l] -= lim * CW[k - 1, m, l]
                        for l in range(nb):
                            T[i, 6 + l] -= lim * XW[k - 1, m, l]
        _solve6(S, T, 6 + nb)
        for i in range(6):
            for l in range(6):
                CW[k, i, l] = T[i, l]
            for l in range(nb):
                XW[k, i, l] = T[i, 6 + l]
    for k in range(M - 2, -1, -1):
        for i in range(6):
            for l in range(nb):
                acc = 0.0
                for m in range(6):
                    acc += CW[k, i, m] * XW[k + 1, m, l]
                XW[k, i, l] -= acc
    # border block n-1: A[n-1][0] = UN[n-1], A[n-1][n-2] = UN[n-2]^T
    for i in range(6):
        for l in range(6):
            S[i, l] = AN[n - 1, i, l]
        for c in range(nr):
            T[i, c] = RHS[n - 1, i, c]
        for m in range(6):
            a0 = UN[n - 1, i, m]
            a1 = UN[M - 1, m, i]
            for l in range(6):
                S[i, l] -= a0 * XW[0, m, nr + l] + a1 * XW[M - 1, m, nr + l]
            for c in range(nr):
                T[i, c] -= a0 * XW[0, m, c] + a1 * XW[M - 1, m, c]
    _solve6(S, T, nr)
    for i in range(6):
        for c in range(nr):
            RHS[n - 1, i, c] = T[i, c]
    for j in range(M):
        for i in range(6):
            for c in range(nr):
                acc = XW[j, i, c]
                for m in range(6):
                    acc -= XW[j, i, nr + m] * T[m, c]
                RHS[j, i, c] = acc


@inline
def _chol6(S, L):
    """Cholesky factor of the symmetric 6 x 6 S (its lower triangle read) into L's lower
    triangle, the diagonal holding the reciprocals 1 / L_kk.  False if S is not positive
    definite (a non-positive or NaN pivot)."""
    for k in range(6):
        for i in range(k, 6):
            acc = S[i, k]
            for p in range(k):
                acc -= L[i, p] * L[k, p]
            if i == k:
                if not acc > 0.0:
                    return False
                L[k, k] = 1.0 / math.sqrt(acc)
            else:
                L[i, k] = acc * L[k, k]
    return True


@inline
def _forward6(L, X, c0, nc):
    """X[:, c0:c0 + nc] <- L^-1 X[:, c0:c0 + nc] (L from _chol6)."""
    for c in range(c0, c0 + nc):
        for k in range(6):
            acc = X[k, c]
            for p in range(k):
                acc -= L[k, p] * X[p, c]
            X[k, c] = acc * L[k, k]


@inline
def _backward6(L, x):
    """x <- L^-T x (one column; L from _chol6)."""
    for k in range(5, -1, -1):
        acc = x[k]
        for p in range(k + 1, 6):
            acc -= L[p, k] * x[p]
        x[k] = acc * L[k, k]


@njit
def chain_forward(AN, UN, RH, ZF, n, j0, LW, CW):
    """Forward sweep of the open ring's block Cholesky, chain j0, j0 + 1, ... (mod n; the
    ring open before j0, UN[j0 - 1] = 0; a further gap leaves its coupling out): LW[j] the
    diagonal block's factor, CW[j] = L_j^-1 UN[j] (W_j, when j touches the next), RH[j, :, 0]
    <- the forward-solved right-hand side, RH[j, :, 1:7] <- Z_j = (L^-1 B')_j where needle j
    carries a coupling column (ZF[j] > 0 on entry: its own; on return: its own or filled in
    along the chain; elsewhere Z_j = 0 and left as is).  False if a block is not positive
    definite (LW, CW, RH and ZF then partly written: coupled_solve sets RH, ZF again)."""
    prev = -1
    for m in range(n):
        j = (j0 + m) % n
        L = LW[j]
        S = CW[j]    # scratch for the Schur-updated block until W_j is written over it
        for i in range(6):
            for l in range(i + 1):
                S[i, l] = AN[j, i, l]
        if prev >= 0:   # S -= W_prev^T W_prev, rhs -= W_prev^T Y_prev
            W = CW[prev]
            if ZF[prev] > 0.0:
                ZF[j] = 1.0
            nc = 7 if ZF[j] > 0.0 else 1
            for i in range(6):
                for l in range(i + 1):
                    acc = 0.0
                    for q in range(6):
                        acc += W[q, i] * W[q, l]
                    S[i, l] -= acc
                for c in range(nc):
                    acc = 0.0
                    if c == 0 or ZF[prev] > 0.0:
                        for q in range(6):
                            acc += W[q, i] * RH[prev, q, c]
                    RH[j, i, c] -= acc
        if not _chol6(S, L):
            return False
        _forward6(L, RH[j], 0, 7 if ZF[j] > 0.0 else 1)
        nxt = m < n - 1 and touching(UN[j])
        if nxt:
            for i in range(6):
                for l in range(6):
                    S[i, l] = UN[j, i, l]
            _forward6(L, S, 0, 6)
        prev = j if nxt else -1
    return True


@njit
def chain_backward(RH, ZF, y, UN, n, j0, LW, CW, X):
    """Back substitution of the open ring after chain_forward: x_j = L_j^-T (Y_j - Z_j y -
    W_j x_next) along the chain backwards (y: the roller's solution), into X (n x 6)."""
    for m in range(n - 1, -1, -1):
        j = (j0 + m) % n
        xj = X[j]
        for i in range(6):
            acc = RH[j, i, 0]
            if ZF[j] > 0.0:
                for c in range(6):
                    acc -= RH[j, i, 1 + c] * y[c]
            xj[i] = acc
        if m < n - 1 and touching(UN[j]):
            jn = (j + 1) % n
            W = CW[j]
            for i in range(6):
                acc = 0.0
                for l in range(6):
                    acc += W[i, l] * X[jn, l]
                xj[i] -= acc
        _backward6(LW[j], xj)
