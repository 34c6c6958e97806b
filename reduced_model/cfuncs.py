"""What the models written as scalar functions over flat arrays share
(reduced_model/analytic_kernel.py, driveline/mounts.py): writing their outputs only when every one is finite, and, at build time
(fmu_src/aot.py), their compiled functions as the C functions the native FMI layer calls
(fmu_src/native/native_model.h): int32_t f(double **args), args = (T, IN, X, OUT, W, TH)."""
import math
import re

NOTE_ARGS = 4   # the numbers a note carries (the native layer words four)


def leave_note(W, at, most, code, a0, a1, a2, a3):
    """Leave a note (code, four numbers) for the FMU's log in W's notes at ``at`` (a count, then
    the notes); beyond ``most`` notes it is dropped."""
    n = int(W[at])
    if n >= most:
        return
    k = at + 1 + n * (1 + NOTE_ARGS)
    W[k] = code
    W[k + 1] = a0
    W[k + 2] = a1
    W[k + 3] = a2
    W[k + 4] = a3
    W[at] = n + 1


def worded_notes(W, at, text):
    """[(level, message)] of the notes W holds at ``at`` (leave_note's), each worded by its
    printf format in ``text`` ((level, format) a code), a note starting with "; " joined to
    the one before: as the native layer words them (fmu_src/native/fmi2_native.c)."""
    out = []
    for n in range(int(W[at])):
        k = at + 1 + n * (1 + NOTE_ARGS)
        level, fmt = text[int(W[k])]
        used = len(re.findall(r"%[^%]", fmt.replace("%%", "")))   # (printf ignores the rest)
        msg = fmt % tuple(float(W[k + 1 + i]) for i in range(used))
        if msg.startswith("; ") and out:
            prev_level, prev = out[-1]
            out[-1] = (prev_level, prev + (msg[2:] if prev.endswith(": ") else msg))
        else:
            out.append((level, msg))
    return out


def native_layout(by_name, params, inputs, outputs, check_order, sizes, notes_at, most, text,
                  state_problems) -> dict:
    """What fmu_src/native_fmu.py needs of a model over these arrays: where each variable lives
    (params, inputs, outputs: the names in T's, IN's and OUT's order), the parameter table
    (by_name), the order the variables are checked in at initialisation, the arrays' sizes
    (T, IN, X, OUT, W) and the notes' place and wording (text: (level, printf format) a code;
    state_problems: why a state is refused, a code)."""
    arrays = {n: ("IN_T", i) for i, n in enumerate(params)}
    arrays.update({n: ("IN_IN", i) for i, n in enumerate(inputs)})
    arrays.update({n: ("IN_OUT", i) for i, n in enumerate(outputs)})
    return {"by_name": by_name, "arrays": arrays, "check_order": list(check_order),
            "sizes": dict(zip(("T", "IN", "X", "OUT", "W"), sizes), TH=2),
            "notes": {"at": notes_at, "args": NOTE_ARGS, "max": most, "text": text,
                      "state_problems": state_problems}}


def compile_over(g, names, jit):
    """g's functions ``names`` as jit copies whose globals are g, so that they call each other
    compiled (g updated in place and returned); the modules they come from stay plain Python."""
    import types
    for name in names:
        f = g[name]
        g[name] = jit(types.FunctionType(f.__code__, g, f.__name__, f.__defaults__,
                                         f.__closure__))
    return g


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
    """numba cfuncs of g's init, step and, where g has them, end, check_state and the step's
    parts (njit functions: init(T, IN, X, OUT, W), step(T, IN, X, OUT, W, t, h), end as init,
    check_state(T, X) or (T, IN, X, W), step_units(T), step_begin as step, step_unit(T, X, W,
    i), step_finish(T, X, OUT, W, ok); W the instance's work); sizes: the lengths of T, IN,
    X, OUT, W."""
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
    if "step_unit" in g:   # a step in parts, its units stepped at once (native_model.h)
        units_c, unit_c, begin_c, finish_c = (g["step_units"], g["step_unit"], g["step_begin"],
                                              g["step_finish"])

        def c_units(args):
            return units_c(carray(args[0], (n_p,)))

        def c_begin(args):
            th = carray(args[5], (2,))
            return begin_c(carray(args[0], (n_p,)), carray(args[1], (n_in,)),
                           carray(args[2], (n_x,)), carray(args[3], (n_out,)),
                           carray(args[4], (n_w,)), th[0], th[1])

        def c_unit(args):     # TH[0]: the unit
            return unit_c(carray(args[0], (n_p,)), carray(args[2], (n_x,)),
                          carray(args[4], (n_w,)), int(carray(args[5], (2,))[0]))

        def c_finish(args):   # TH[0]: 1.0 when every unit returned 1
            return finish_c(carray(args[0], (n_p,)), carray(args[2], (n_x,)),
                            carray(args[3], (n_out,)), carray(args[4], (n_w,)),
                            carray(args[5], (2,))[0])
        out.update(step_units=c_units, step_begin=c_begin, step_unit=c_unit,
                   step_finish=c_finish)
    if "end" in g:
        end_c = g["end"]

        def c_end(args):
            return end_c(carray(args[0], (n_p,)), carray(args[1], (n_in,)),
                         carray(args[2], (n_x,)), carray(args[3], (n_out,)),
                         carray(args[4], (n_w,)))
        out["end"] = c_end
    if "state_problem" in g:
        problem_c = g["state_problem"]
        if problem_c.py_func.__code__.co_argcount == 4:   # (T, IN, X, W)
            def c_check(args):
                return problem_c(carray(args[0], (n_p,)), carray(args[1], (n_in,)),
                                 carray(args[2], (n_x,)), carray(args[4], (n_w,)))
        else:                                             # (T, X)
            def c_check(args):
                return problem_c(carray(args[0], (n_p,)), carray(args[2], (n_x,)))
        out["check_state"] = c_check
    return {name: nb.cfunc(sig, error_model="numpy")(f) for name, f in out.items()}
