"""Small dense solve for the linearly implicit steps (numba)."""
from .jit import njit


@njit
def solve_small(A, b, n):
    """Solve A x = b in place (b <- x) for the leading n x n block; Gaussian elimination with
    partial pivoting (A is small and well conditioned: mass minus h times a friction Jacobian)."""
    for k in range(n):
        piv = k
        for i in range(k + 1, n):
            if abs(A[i, k]) > abs(A[piv, k]):
                piv = i
        if piv != k:
            for j in range(n):
                A[k, j], A[piv, j] = A[piv, j], A[k, j]
            b[k], b[piv] = b[piv], b[k]
        for i in range(k + 1, n):
            f = A[i, k] / A[k, k]
            for j in range(k, n):
                A[i, j] -= f * A[k, j]
            b[i] -= f * b[k]
    for k in range(n - 1, -1, -1):
        acc = b[k]
        for j in range(k + 1, n):
            acc -= A[k, j] * b[j]
        b[k] = acc / A[k, k]
