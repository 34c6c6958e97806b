"""How far the adaptive substeps run from their budget in ordinary scenes (harness/budget_use.py
says what is run).  Prints a markdown table.

    python -m benchmarks.step_budget [--md FILE]
"""
from __future__ import annotations

import argparse

from harness.budget_use import table


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--md", help="also write the table to this file")
    a = ap.parse_args(argv)
    text = table()
    print(text)
    if a.md:
        with open(a.md, "w") as f:
            f.write(text + "\n")


if __name__ == "__main__":
    main()
