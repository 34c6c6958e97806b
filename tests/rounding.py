"""Bounds for tests that compare two computations of one quantity and differ only by rounding:
each scales with the machine epsilon and the size of what it compares, with a margin for other
CPUs and libms (their last bits differ, never more)."""
import numpy as np

EPS = np.finfo(float).eps


def ulps(n: float, scale) -> float:
    """n units in the last place of a quantity of size ``scale``."""
    return n * EPS * np.abs(scale)


def solve_error(A: np.ndarray, x: np.ndarray) -> float:
    """Norm-wise bound on the difference of two backward-stable solves of A x = b (LU, block
    elimination): each is within n eps cond(A) ||x|| of x (Higham, Accuracy and Stability of
    Numerical Algorithms, 7.1), twice that for two of them, times 4 for the constant."""
    return 8 * A.shape[0] * EPS * np.linalg.cond(A) * np.linalg.norm(x)
