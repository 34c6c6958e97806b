"""Run-ups under a driveline master (issue 33): the contact model's whole joint (300 N m, 8 deg)
whirled from 2 to 40 Hz over 0.5 s and 3 s, the master holding omega over each communication
step of 1e-4, 2e-5 and 1e-3 s; order 3 of Fz_joint of the revolution nearest 5, 10, 20 and
35 Hz against the settled constant-speed value at that revolution's mean speed (1e-3 s up to
10 Hz: faster, it leaves too few samples a revolution to read order 3 to 1 %).  Prints a
markdown table (about 15 s).

    python benchmarks/runups.py
"""
from __future__ import annotations

import time

from harness.input_transients import runup, settle

RUNS = ((0.5, 1e-4), (0.5, 2e-5), (0.5, 1e-3), (3.0, 1e-4), (3.0, 2e-5), (3.0, 1e-3))
TARGETS = (5.0, 10.0, 20.0, 35.0)


def rows():
    """[(duration [s], step [s], target [Hz], revolution's mean speed [Hz], order 3 [N],
    settled order 3 [N], difference [%])]."""
    out = []
    for duration, dt in RUNS:
        revs = runup({}, 3, 2.0, 40.0, duration, dt=dt)
        seen = set()
        for target in TARGETS if dt < 1e-3 else TARGETS[:2]:
            f, a = min(revs, key=lambda r: abs(r[0] - target))
            if f in seen:     # (over 0.5 s the first whole revolution is already at 7 Hz)
                continue
            seen.add(f)
            ref = settle({}, 3, f, cycles=4)[1]
            out.append((duration, dt, target, f, a, ref, 100 * (a / ref - 1)))
    return out


def main():
    t0 = time.time()
    print("| run-up | step [s] | near [Hz] | revolution's speed [Hz] | order 3 [N] | "
          "settled [N] | difference [%] |")
    print("|---|---|---|---|---|---|---|")
    for duration, dt, target, f, a, ref, d in rows():
        print(f"| 2 -> 40 Hz in {duration:g} s | {dt:g} | {target:g} | {f:.2f} | {a:.2f} | "
              f"{ref:.2f} | {d:+.2f} |")
    print(f"(three rollers, 300 N m, 8 deg; {time.time() - t0:.0f} s)")


if __name__ == "__main__":
    main()
