"""PNG plots of a comparison (matplotlib, Agg backend; imported only when plots are asked for)."""
from __future__ import annotations

import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from reduced_model import scene as scene_mod  # noqa: E402
from reduced_model.thrust import time_series  # noqa: E402


def last_cycle(run: dict, omega: float):
    """Mask of the last whole whirl cycle and the whirl angle there [deg, 0-360)."""
    t = run["time"]
    x = omega * t
    m = x >= x[-1] - 2 * math.pi - 1e-9
    return m, np.degrees(np.mod(x[m], 2 * math.pi))


def _sorted(xdeg, *ys):
    i = np.argsort(xdeg)
    return (xdeg[i],) + tuple(y[i] for y in ys)


def _save(fig, path):
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def scene_title(sc: dict, omega: float) -> str:
    """The scene under a plot's title, in two lines that fit the 8-inch figures: angle, whirl
    [rad/s in, Hz out] and load on the first, the contact model on the second."""
    from .compare import BEARING_NAMES
    tq = sc.get("torque", 0.0)
    load = (f"torque {tq:.6g} N m ({scene_mod.pressing_load(sc['F_press'], tq, sc['s']):.0f} N "
            f"a roller)" if tq else f"F_press = {sc['F_press']:.6g} N")
    rollers = "whole joint" if int(sc.get("n_rollers", 1)) == 3 else "one roller"
    return (f"theta = {math.degrees(sc['theta']):.1f} deg, {omega / (2 * math.pi):.3g} Hz, {load}\n"
            f"{BEARING_NAMES[int(sc['bearing'])]}, traverse = {str(sc['traverse']).lower()}, {rollers}")


def compare_plots(r: dict, out: str | Path) -> list[Path]:
    """Write the five comparison plots into ``out``; returns their paths."""
    from .compare import spectrum
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    ra, rc, w = r["_runs"]["analytic"], r["_runs"]["contact"], r["_runs"]["omega"]
    sc = r["scene"]
    title = scene_title(sc, w)
    paths = []
    ma, xa = last_cycle(ra, w)
    mc, xc = last_cycle(rc, w)

    fig, ax = plt.subplots(figsize=(8, 4.5))
    ax.plot(*_sorted(xa, ra["Fz_mod"][ma]), label="analytic FMU (Eqs. 18-27 + spin inertia)")
    ax.plot(*_sorted(xc, rc["Fz_mod"][mc]), label="contact FMU")
    ax.set(xlabel="whirl angle wt [deg]", ylabel="modified thrust Fz' [N]",
           title=f"Modified thrust over one whirl cycle\n{title}", xlim=(0, 360))
    ax.grid(alpha=0.3)
    ax.legend()
    paths.append(_save(fig, out / "thrust_cycle.png"))

    fig, ax = plt.subplots(figsize=(8, 4.5))
    k = np.arange(1, 11)
    ax.bar(k - 0.2, spectrum(ra, w), width=0.4, label="analytic FMU")
    ax.bar(k + 0.2, spectrum(rc, w), width=0.4, label="contact FMU")
    ax.set(xlabel="rotating order [-]", ylabel="amplitude of Fz' [N]", xticks=k,
           title=f"Order spectrum of the modified thrust\n{title}")
    ax.grid(alpha=0.3, axis="y")
    ax.legend()
    paths.append(_save(fig, out / "order_spectrum.png"))

    fig, ax = plt.subplots(figsize=(6, 5))
    ax.plot(rc["contact_z"][mc] * 1e3, rc["contact_y"][mc] * 1e3)
    ax.set(xlabel="contact point along the groove z [mm]",
           ylabel="contact point across the groove y [mm]",
           title="Contact-point locus on the groove (Fig. 20)")
    ax.grid(alpha=0.3)
    paths.append(_save(fig, out / "contact_locus.png"))

    fig, ax = plt.subplots(figsize=(8, 4.5))
    ax.plot(*_sorted(xc, rc["dFx"][mc]), label="dFx = Fx - F_press")
    ax.plot(*_sorted(xc, rc["Fy"][mc]), label="Fy")
    ax.set(xlabel="whirl angle wt [deg]", ylabel="force on the groove [N]", xlim=(0, 360),
           title=f"Pressing-force change and lateral force, contact FMU (Fig. 11)\n{title}")
    ax.grid(alpha=0.3)
    ax.legend()
    paths.append(_save(fig, out / "forces_dFx_Fy.png"))

    fig, ax = plt.subplots(figsize=(8, 4.5))
    asc = {k: v for k, v in sc.items() if "analytic" in scene_mod.BY_NAME[k].models}
    asc = scene_mod.validate(asc, "analytic")
    xs = np.linspace(0, 2 * math.pi, 721)
    ts = time_series(asc, xs)
    ax.plot(np.degrees(xs), ts["v1"] * 1e3, label="v1, pitching (Eq. 19)")
    ax.plot(np.degrees(xs), ts["v2"] * 1e3, label="v2, rolling (Eq. 20)")
    ax.plot(np.degrees(xs), ts["V"] * 1e3, label="V = v1 + v2 (Eq. 24)")
    xcs, slip = _sorted(xc, rc["slip_speed"][mc])
    ax.plot(xcs, slip * 1e3, "k--", lw=1, label="|slip| at the contact, contact FMU")
    # the roller centre sits (Rg - r)/Rg of the way out along the contact normal
    ydot = np.gradient(rc["contact_y"], rc["time"]) * (sc["r_groove"] - sc["r_roller"]) / sc["r_groove"]
    ax.plot(*_sorted(xc, ydot[mc] * 1e3), ":", label="traverse speed of the roller centre, contact FMU")
    ax.set(xlabel="whirl angle wt [deg]", ylabel="sliding velocity [mm/s]", xlim=(0, 360),
           title=f"Sliding velocities of the roller on the groove (Fig. 22)\n{title}")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    paths.append(_save(fig, out / "sliding_velocities.png"))
    return paths
