"""The contact FMU's check of a state a host sets (fmi2SetFMUstate; lifecycle.py compiles
these with its own functions): a roller's parameters and operating point must be what this
instance's table and the state's inputs give, its history and motion within state_check.py's
bounds, a free spider's pose and rates within its own.  Scalar functions over the arrays of
fmu_arrays.py, as lifecycle.py's."""
import math

from reduced_model.scene import SPIDER_FREE
from . import layout as K
from .fmu_arrays import OMEGA, PLUNGE_SPEED, THETA, W_SAVE, X_HS, X_OP, X_P, X_STARTED, \
    X_STEPS, X_TIME, X_Y, X_Y2, op_row, shape_of
from .kernel import derive_op
from .oppoint import OP_DERIVED, P_DERIVED
from .roller_setup import (T_BEARING, T_D_NEEDLE, T_L_NEEDLE, T_R_BORE, T_R_GROOVE, T_R_ROLLER,
                           T_S, T_SPIDER, kernel_params)
from .state_check import history_bound, roller_bound, speed_limit, spider_bounds


def roller_problem(T, IN, X, W, i, n, resolved, ny, ys):
    """0 when roller i's state can be stepped (state_check.check_roller_state's bounds), else a
    code of STATE_PROBLEMS."""
    P = X[X_P + i * K.P_LEN:X_P + (i + 1) * K.P_LEN]
    OP = X[X_OP + op_row(n, resolved, i) * K.OP_LEN:X_OP + (op_row(n, resolved, i) + 1) * K.OP_LEN]
    hs = X[X_HS + i * K.H_LEN:X_HS + (i + 1) * K.H_LEN]
    # its parameters: what the table's values derive; its operating point: what its inputs do
    S = W[W_SAVE:W_SAVE + K.P_LEN]
    kernel_params(T, S)
    for j in range(K.P_LEN):
        derived = False
        for d in P_DERIVED:
            if j == d:
                derived = True
        if not derived and P[j] != S[j]:
            return 2
    for j in P_DERIVED:
        S[j] = P[j]
    SO = W[W_SAVE + K.P_LEN:W_SAVE + K.P_LEN + K.OP_LEN]
    for j in range(K.OP_LEN):
        SO[j] = OP[j]
    SO[K.OP_KEY + 4] = math.nan      # derived again at its inputs
    derive_op(S, SO)
    for j in OP_DERIVED:
        if SO[j] != OP[j]:
            return 3
    for j in P_DERIVED:
        if j != K.P_DF and S[j] != P[j]:
            return 3
    if not (0.0 <= P[K.P_DF] <= 2.0) or OP[K.OP_NOSTEP] != 0.0:
        return 3
    if history_bound(P[K.P_VST_OP], hs) != 0:
        return 4
    # the speeds the driven motion makes, at the larger of the inputs and the key
    v = speed_limit(T[T_S], T[T_R_ROLLER], max(abs(IN[THETA]), abs(OP[K.OP_KEY])),
                    max(abs(IN[OMEGA]), abs(OP[K.OP_KEY + 1])),
                    max(abs(IN[PLUNGE_SPEED]), abs(OP[K.OP_KEY + 5])))
    for k in range(2):
        Y = X[(X_Y if k == 0 else X_Y2) + i * ys:(X_Y if k == 0 else X_Y2) + i * ys + ny]
        code = roller_bound(Y, T[T_BEARING] != K.BEAR_IDEAL, T[T_L_NEEDLE], T[T_D_NEEDLE],
                            T[T_R_ROLLER], T[T_R_BORE], v)[0]
        if code != 0:
            return code
    return 0


def state_problem(T, IN, X, W):
    """0 when the state X is one the model can step (every value finite is the layer's
    check), else a code of STATE_PROBLEMS: its flags or counts none the model writes (1), a
    roller's parameters not this instance's (2), its operating point not its inputs' (3), its
    transition velocity, substep or counts out of range (4), its motion beyond the scene's
    bounds (5-8: state_check.py's)."""
    if X[X_STARTED] != 0.0 and X[X_STARTED] != 1.0:
        return 1
    if X[X_TIME] < 0.0 or X[X_STEPS] < 0.0:
        return 1
    if X[X_STARTED] == 0.0:   # the first step starts it afresh
        return 0
    n, resolved, nn, ns, ny, ys = shape_of(T)
    for i in range(n):
        code = roller_problem(T, IN, X, W, i, n, resolved, ny, ys)
        if code != 0:
            return code
    if T[T_SPIDER] == SPIDER_FREE:
        return spider_problem(T, IN, X)
    return 0


def spider_problem(T, IN, X):
    """0 when a free spider's state (OP's header row) can be stepped (state_check's
    spider_bounds), else a code of STATE_PROBLEMS."""
    h = X[X_OP:X_OP + K.OP_LEN]
    if h[K.OP_SP_SET] != 0.0 and h[K.OP_SP_SET] != 1.0:
        return 1
    return spider_bounds(h[K.OP_SP_QX], h[K.OP_SP_QY], h[K.OP_SP_PSI], h[K.OP_SP_VX],
                         h[K.OP_SP_VY], h[K.OP_SP_VPSI], T[T_S], T[T_R_GROOVE],
                         T[T_S] * abs(IN[OMEGA]))
