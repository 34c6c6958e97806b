"""Parameter sweeps over an FMU with dask: local processes by default, or an existing
dask.distributed cluster.  Each point is one FMPy run in its own subprocess."""
from __future__ import annotations

import csv
import itertools
import math
from pathlib import Path

import numpy as np

from reduced_model import scene as scene_mod
from reduced_model.orders import last_cycle_orders

from .fmus import ensure_fmu
from .runs import FmuRunError, default_dt, run_settled, settle_request

FMUS = {"contact": "TripodRoller", "analytic": "TripodRollerAnalytic"}
COLUMNS = ("order1_amplitude", "order1_phase_deg", "order3_amplitude", "order3_phase_deg",
           "cycles", "settled", "cycle_change", "wall_s", "error")


def parse_grid(spec: str) -> tuple[str, np.ndarray]:
    """'NAME=START:STOP:N' (SI units) -> (name, N values from START to STOP inclusive)."""
    if "=" not in spec or spec.count(":") != 2:
        raise ValueError(f"--grid expects NAME=START:STOP:N, got '{spec}'")
    name, rng = spec.split("=", 1)
    name = name.strip()
    if name not in scene_mod.BY_NAME:
        raise ValueError(f"--grid: unknown parameter '{name}'")
    a, b, n = rng.split(":")
    try:
        a, b, n = float(a), float(b), int(n)
    except ValueError:
        raise ValueError(f"--grid {name}: START and STOP must be numbers and N an integer") from None
    if n < 1:
        raise ValueError(f"--grid {name}: N = {n}; allowed range N >= 1")
    # (each point the double nearest its decimal: 0.15, not linspace's 0.15000000000000002)
    vals = np.array([float(f"{v:.15g}") for v in np.linspace(a, b, n)])
    for v in vals:
        scene_mod.check_value(name, v if scene_mod.BY_NAME[name].kind == "real" else int(round(v)))
    return name, vals


def points(grid: dict) -> list[dict]:
    names = list(grid)
    return [dict(zip(names, combo)) for combo in itertools.product(*(grid[n] for n in names))]


def point_values(base: dict, point: dict) -> dict:
    """The start values of one grid point: base with the point's values, typed as the
    parameter table declares them."""
    sv = dict(base)
    for k, v in point.items():
        p = scene_mod.BY_NAME[k]
        sv[k] = float(v) if p.kind == "real" else int(round(v))
    return sv


def check(grid: dict, base: dict, model: str, max_cycles: int | None) -> None:
    """Refuse, before any run, what no grid point could run: a cycle cap out of range, a point
    whose scene its model refuses (a cross-parameter rule, e.g. r_groove above r_roller), or
    a whirl speed without cycles to analyse.  Raises ValueError naming the point."""
    settle_request(1.0, ["Fz_mod"], max_cycles=max_cycles)
    for point in points(grid):
        sv = point_values(base, point)
        at = ", ".join(f"{k} = {sv[k]:g}" for k in point)
        try:
            scene_mod.validate(sv, model)
        except ValueError as e:
            raise ValueError(f"grid point {at}: {e}") from None
        if sv.get("omega", scene_mod.BY_NAME["omega"].default) <= 0:
            raise ValueError(f"grid point {at}: omega must be > 0 for an order analysis")


def run_point(fmu: str, base: dict, point: dict, max_cycles: int | None, dt: float | None,
              signal: str = "Fz_mod") -> dict:
    """One grid point: simulate whole cycles until ``signal`` is periodic (or max_cycles), then
    orders 1 and 3 over the last whole cycle, the cycles used and the last cycle-to-cycle
    change (relative, complex; reduced_model.steady)."""
    sv = point_values(base, point)
    omega = sv.get("omega", scene_mod.BY_NAME["omega"].default)
    row = {**point, **{c: math.nan for c in COLUMNS[:-1]}, "error": ""}
    try:
        if omega <= 0:
            raise ValueError("omega must be > 0 for an order analysis")
        r = run_settled(fmu, sv, omega, [signal], default_dt(omega) if dt is None else dt,
                        max_cycles)
        o = last_cycle_orders(r["time"], r[signal], omega * r["time"], (1, 3))
        st = r["settle"]
        row.update(order1_amplitude=o[1][0], order1_phase_deg=o[1][1],
                   order3_amplitude=o[3][0], order3_phase_deg=o[3][1], cycles=st["cycles"],
                   settled=st["settled"], cycle_change=st["worst"]["complex_rel"],
                   wall_s=r["wall_s"])
    except (FmuRunError, ValueError) as e:   # a failed point is reported, not fatal
        row["error"] = str(e).splitlines()[0][:300]
    return row


def sweep(grid: dict, base: dict | None = None, model: str = "contact",
          max_cycles: int | None = None,
          dt: float | None = None, scheduler: str | None = None, workers: int = 2,
          progress: bool = True) -> list[dict]:
    """Run the grid in parallel.

    dt: communication step [s] (None: harness.runs.default_dt of each point's whirl speed).
    scheduler: None = local processes (dask multiprocessing, ``workers`` of them);
    "sync" = serial in this process; otherwise the address of a running dask.distributed
    scheduler (e.g. "tcp://10.0.0.5:8786").  Rows come back in grid order.
    """
    import dask
    base = dict(base or {})
    if not 1 <= workers <= 1024:
        raise ValueError(f"--workers = {workers}: allowed range [1, 1024]")
    check(grid, base, model, max_cycles)
    fmu = str(ensure_fmu(FMUS[model]))       # build once, before any worker starts
    pts = points(grid)
    if scheduler and scheduler != "sync":
        from distributed import Client, progress as dprogress
        with Client(scheduler) as client:
            futs = client.map(run_point, [fmu] * len(pts), [base] * len(pts), pts,
                              [max_cycles] * len(pts), [dt] * len(pts), pure=False)
            if progress:
                dprogress(futs)
            return client.gather(futs)
    tasks = [dask.delayed(run_point)(fmu, base, p, max_cycles, dt) for p in pts]
    kw = {"scheduler": "sync"} if scheduler == "sync" else {"scheduler": "processes",
                                                              "num_workers": workers}
    if progress:
        from dask.diagnostics import ProgressBar
        with ProgressBar():
            return list(dask.compute(*tasks, **kw))
    return list(dask.compute(*tasks, **kw))


# the result columns' units (SI; a name ending in _deg or _s says its own)
UNITS = {"order1_amplitude": "N", "order3_amplitude": "N"}


def header(name: str) -> str:
    """A CSV column's heading: the name and, where the name does not say it, its unit in
    brackets (a grid parameter's from the table; none for dimensionless columns)."""
    p = scene_mod.BY_NAME.get(name)
    unit = UNITS.get(name) or (p.unit if p is not None and p.kind == "real" else "1")
    return name if unit == "1" else f"{name} [{unit}]"


def write_csv(rows: list[dict], path) -> Path:
    """sweep.csv: one row a grid point, each heading with its unit (header)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow([header(k) for k in rows[0]])
        w.writerows([list(r.values()) for r in rows])
    return path


def plot(rows: list[dict], grid: dict, path) -> Path:
    """Order-3 amplitude over the grid: a line for one swept parameter, contours for two."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    names = list(grid)
    a3 = np.array([r["order3_amplitude"] for r in rows], float)
    fig, ax = plt.subplots(figsize=(7, 4.5))
    unit = {n: scene_mod.BY_NAME[n].unit for n in names}
    if len(names) == 1:
        ax.plot(grid[names[0]], a3, "o-")
        ax.set(xlabel=f"{names[0]} [{unit[names[0]]}]", ylabel="order 3 amplitude of Fz' [N]")
    else:
        x, y = grid[names[0]], grid[names[1]]
        z = a3.reshape(len(x), len(y), -1)[:, :, 0] if len(names) > 2 else a3.reshape(len(x), len(y))
        cs = ax.contourf(y, x, z, levels=12)
        fig.colorbar(cs, label="order 3 amplitude of Fz' [N]")
        ax.set(xlabel=f"{names[1]} [{unit[names[1]]}]", ylabel=f"{names[0]} [{unit[names[0]]}]")
        if len(names) > 2:
            ax.set_title(f"(first value of {', '.join(names[2:])})")
    ax.set_title("Order 3 of the modified thrust over the sweep" + ("" if len(names) < 3 else ""))
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return Path(path)
