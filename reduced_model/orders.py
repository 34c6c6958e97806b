"""Order (rotating-order) analysis over whole whirl cycles.

Convention (model.md): order k is a_k sin(k w t + p_k), a_k >= 0, p_k in degrees wrapped
to (-180, 180], referred to the time origin t = 0 (whirl angle 0).
"""
import numpy as np


def wrap_deg(p):
    """Wrap an angle in degrees to (-180, 180]."""
    return 180.0 - np.mod(180.0 - np.asarray(p, dtype=float), 360.0)


def order_spectrum(y, cycles=1, orders=range(1, 11)):
    """Amplitudes and phases of the given orders of ``y``.

    ``y`` holds uniform samples over exactly ``cycles`` whole cycles, endpoint excluded,
    starting at whirl angle 0.  Returns (amplitudes [unit of y], phases [deg]) as arrays.
    """
    y = np.asarray(y, dtype=float)
    n = y.size
    X = np.fft.rfft(y)
    ks = np.asarray(list(orders), dtype=int)
    idx = ks * int(cycles)
    if np.any(idx >= n // 2):
        raise ValueError(f"orders up to {ks.max()} need more than {2 * idx.max()} samples, got {n}")
    c = X[idx]
    amp = 2.0 * np.abs(c) / n
    # a sin(k x + p) = a cos(k x + p - pi/2): FFT phase + 90 deg
    ph = wrap_deg(np.degrees(np.angle(c)) + 90.0)
    ph = np.where(amp > 1e-12 * max(1.0, np.abs(y).max()), ph, 0.0)
    return amp, ph


def order_component(y, k, cycles=1):
    """(amplitude, phase_deg) of order ``k`` of uniform samples over whole cycles."""
    a, p = order_spectrum(y, cycles, [k])
    return float(a[0]), float(p[0])


def last_cycle_orders(t, y, whirl_angle, orders=(1, 3), n=None, x_end=None):
    """Orders of ``y`` over the last whole whirl cycle of a run.

    t [s], y, whirl_angle [rad] are arrays of one run (whirl angle may vary in rate).  The last
    whole cycle, the one ending at whirl angle ``x_end`` (default the run's last sample; an
    earlier cycle's end need not be a sample), is resampled uniformly in whirl angle (``n``
    points, default the number of samples it holds) and analysed; phases refer to whirl angle 0.
    Returns {k: (amplitude, phase_deg)}.
    """
    t = np.asarray(t, float)
    y = np.asarray(y, float)
    x = np.asarray(whirl_angle, float)
    x_end = x[-1] if x_end is None else float(x_end)
    x0 = x_end - 2.0 * np.pi
    # short of a whole cycle by the tolerance of whole-cycle counting (steady.whole_cycles)
    # at most: the window starts at the run's start
    if x0 < x[0] - 2.0 * np.pi * 1e-9 or x_end > x[-1] + 1e-12:
        raise ValueError("the run holds less than one whole whirl cycle")
    span = 2.0 * np.pi
    if x0 < x[0]:
        x0, span = x[0], x_end - x[0]
    m = (x >= x0 - 1e-12) & (x <= x_end + 1e-12)
    if n is None:
        n = max(int(m.sum()) - 1, 64)
    xs = x0 + span * np.arange(n) / n
    ys = np.interp(xs, x, y)
    amp, ph = order_spectrum(ys, 1, orders)
    # samples start at x0, not 0: refer phase to whirl angle 0
    ph = wrap_deg(ph - np.degrees(np.asarray(orders) * x0))
    ph = np.where(amp > 0, ph, 0.0)
    return {int(k): (float(a), float(p)) for k, a, p in zip(orders, amp, ph)}
