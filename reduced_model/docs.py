"""Markdown documentation generated from the parameter table (one source of truth)."""
from .scene import INT_OUTPUTS, OUTPUTS, PARAMS


def _start(p):
    if p.kind == "bool":
        return "true" if p.default else "false"
    return f"{p.default:.6g}"


def params_markdown() -> str:
    """The parameter table as Markdown: name, start, unit, range, models, description."""
    rows = ["| name | start | unit | range | causality | models | description |",
            "|---|---|---|---|---|---|---|"]
    for p in PARAMS:
        rows.append(f"| `{p.name}` | {_start(p)} | {p.unit} | {p.range_text()} | {p.causality} "
                    f"| {', '.join(sorted(p.models))} | {p.description} |")
    return "\n".join(rows)


def outputs_markdown() -> str:
    """The contact FMU's outputs as Markdown (causality output, variability continuous)."""
    rows = ["| name | unit | causality | variability | description |", "|---|---|---|---|---|"]
    for name, unit, desc in OUTPUTS:
        rows.append(f"| `{name}` | {unit} | output | continuous | {desc} |")
    for name, desc, owner in INT_OUTPUTS:
        rows.append(f"| `{name}` | 1 (Integer, {owner} FMU only) | output | discrete | {desc} |")
    return "\n".join(rows)


def variables_markdown() -> str:
    return params_markdown() + "\n\n" + outputs_markdown()
