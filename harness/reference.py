"""Per-FMU documentation like the Modelica Reference-FMUs: a variables table, a reference
result CSV and a plot, generated into docs/ (make docs); a test re-runs and checks the CSV."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from .fmus import FMU_NAMES, ROOT, ensure_fmu
from .runs import run_fmu

DOCS = ROOT / "docs"
REF_OUTPUTS = ("Fx", "Fy", "Fz", "Fz_mod")
REF_INTERVAL = 1e-4      # communication step of the reference run [s]
REF_EVERY = 5            # keep every 5th sample in the CSV (5e-4 s)


def variables_markdown(fmu) -> str:
    """Variables of a built FMU: name, start, unit, causality, variability, description."""
    from fmpy import read_model_description
    md = read_model_description(str(fmu))
    rows = ["| name | start | unit | causality | variability | description |",
            "|---|---|---|---|---|---|"]
    for v in md.modelVariables:
        # outputs without a start value are calculated at initialisation (the start state's)
        start = v.start if v.start is not None else (v.initial or "")
        unit = v.unit or ("" if v.type != "Real" else "1")
        du = f" (display {v.displayUnit})" if getattr(v, "displayUnit", None) else ""
        rows.append(f"| `{v.name}` | {start} | {unit}{du} | {v.causality} | {v.variability} "
                    f"| {v.description or ''} |")
    return "\n".join(rows)


def reference_run(name: str) -> dict:
    """The DefaultExperiment (two whirl cycles of the paper's scene) at REF_INTERVAL."""
    return run_fmu(ensure_fmu(name), {}, stop_time=0.2, output_interval=REF_INTERVAL)


def reference_table(r: dict) -> np.ndarray:
    cols = [r["time"]] + [r[n] for n in REF_OUTPUTS]
    return np.column_stack(cols)[::REF_EVERY]


def reference_csv_text(tab: np.ndarray) -> str:
    """The reference table as its CSV holds it (10 significant digits)."""
    import io
    f = io.StringIO()
    np.savetxt(f, tab, delimiter=",", header=",".join(("time",) + REF_OUTPUTS), comments="",
               fmt="%.10g")
    return f.getvalue()


def write_docs(names=FMU_NAMES) -> list[Path]:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    DOCS.mkdir(exist_ok=True)
    written = []
    for name in names:
        fmu = ensure_fmu(name)
        r = reference_run(name)
        tab = reference_table(r)
        csv = DOCS / f"{name}_ref.csv"
        csv.write_text(reference_csv_text(tab))
        fig, ax = plt.subplots(figsize=(8, 4.5))
        ax.plot(r["time"], r["Fz_mod"], label="Fz_mod")
        ax.plot(r["time"], r["Fz"], "--", label="Fz")
        ax.set(xlabel="time [s]", ylabel="thrust [N]",
               title=f"{name}: reference result (DefaultExperiment, paper's scene)")
        ax.grid(alpha=0.3)
        ax.legend()
        fig.tight_layout()
        png = DOCS / f"{name}_ref.png"
        fig.savefig(png, dpi=100)
        plt.close(fig)
        md = DOCS / f"{name}.md"
        md.write_text(
            f"# {name}\n\n"
            f"FMI 2.0 co-simulation FMU built by `make fmu` into `build/{name}.fmu`.\n\n"
            f"## Variables\n\n{variables_markdown(fmu)}\n\n"
            f"## Reference result\n\n"
            f"DefaultExperiment (0-0.2 s, two whirl cycles of the paper's scene), communication "
            f"step {REF_INTERVAL:g} s, every {REF_EVERY}th sample: [{csv.name}]({csv.name}) "
            f"(checked by `tests/test_driveline.py`).\n\n![reference result]({png.name})\n")
        written += [md, csv, png]
    return written


if __name__ == "__main__":
    for p in write_docs():
        print(p)
