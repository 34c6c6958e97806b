"""What the models written as scalar functions over flat arrays share (reduced_model/kernel.py,
driveline/mounts.py): writing their outputs only when every one is finite, and, at build time
(fmu_src/aot.py), their compiled functions as the C functions the native FMI layer calls
(fmu_src/native/native_model.h): int32_t f(double **args), args = (P, IN, X, OUT, W, TH)."""
import math


def finite_into(vals, OUT):
    """vals into OUT when every one is finite.  Returns 1, or 2 (a non-finite value; OUT
    untouched)."""
    for v in vals:
        if not math.isfinite(v):
            return 2
    for j in range(len(vals)):
        OUT[j] = vals[j]
    return 1


def c_functions(g, sizes):
    """numba cfuncs of g's init, step and, where g has them, end and check_state (njit
    functions: init(P, IN, X, OUT, W), step(P, IN, X, OUT, W, t, h), end as init,
    check_state(P, X) or (P, IN, X, W), W the instance's work); sizes: the lengths of P, IN, X,
    OUT, W."""
    import numba as nb
    from numba import carray

    n_p, n_in, n_x, n_out, n_w = sizes
    sig = nb.types.int32(nb.types.CPointer(nb.types.CPointer(nb.types.float64)))
    out = {}
    init_c, step_c = g["init"], g["step"]

    def c_init(args):
        return init_c(carray(args[0], (n_p,)), carray(args[1], (n_in,)),
                      carray(args[2], (n_x,)), carray(args[3], (n_out,)),
                      carray(args[4], (n_w,)))

    def c_step(args):
        th = carray(args[5], (2,))
        return step_c(carray(args[0], (n_p,)), carray(args[1], (n_in,)),
                      carray(args[2], (n_x,)), carray(args[3], (n_out,)),
                      carray(args[4], (n_w,)), th[0], th[1])

    out["init"], out["step"] = c_init, c_step
    if "end" in g:
        end_c = g["end"]

        def c_end(args):
            return end_c(carray(args[0], (n_p,)), carray(args[1], (n_in,)),
                         carray(args[2], (n_x,)), carray(args[3], (n_out,)),
                         carray(args[4], (n_w,)))
        out["end"] = c_end
    if "state_problem" in g:
        problem_c = g["state_problem"]
        if problem_c.py_func.__code__.co_argcount == 4:   # (P, IN, X, W)
            def c_check(args):
                return problem_c(carray(args[0], (n_p,)), carray(args[1], (n_in,)),
                                 carray(args[2], (n_x,)), carray(args[4], (n_w,)))
        else:                                             # (P, X)
            def c_check(args):
                return problem_c(carray(args[0], (n_p,)), carray(args[2], (n_x,)))
        out["check_state"] = c_check
    return {name: nb.cfunc(sig, error_model="numpy")(f) for name, f in out.items()}
