"""Where the needle-resolved row's load sits along the trunnion, against the trunnion's stroke
(docs/model.md, "Why the resolved row rocks more"): the needles between a race that strokes and
one that stays, within their axial play.

One roller, needle-resolved bearing, row friction on, three whirl cycles from the start; over
the last: the trunnion's axial stroke relative to the roller (Eq. 7, less the slide and the
offset's share along the trunnion) and d, the bore-loaded needles' mean place from the roller's
centre (harness/row_rocking.py), each peak to peak; d predicted by a play operator,
the needles going half the stroke's way (contact.ROW_CARRY) until their lag behind the trunnion
reaches the play (needle_axial_clearance), then carried by the stop: its peak to peak and its
correlation with d.  The lumped row takes d as half the stroke, without the play.

Usage: python -m benchmarks.row_play [--scenes 3,45000 8,45000 15,45000 20,4500] (about 30 s a
scene)
"""
import argparse
import math

import numpy as np

from harness.row_rocking import play_operator, stroke_and_place
from tripod_model import contact


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scenes", nargs="+", default=["3,45000", "8,45000", "15,45000",
                                                    "20,4500"],
                    help="THETA_DEG,LOAD_N each (default: four)")
    args = ap.parse_args()
    print("| theta [deg] | load [N] | stroke, peak to peak [um] | d, peak to peak [um] | "
          "half the stroke [um] | play operator, peak to peak [um] | its correlation with d |")
    print("|---|---|---|---|---|---|---|")
    for sc in args.scenes:
        th, F = (float(v) for v in sc.split(","))
        a, play = stroke_and_place(math.radians(th), F, 2.0 * math.pi * 10.0)
        stroke, d = a[:, 1], a[:, 2]
        pred = play_operator(stroke, play)
        print(f"| {th:g} | {F:g} | {np.ptp(stroke) * 1e6:.0f} | {np.ptp(d) * 1e6:.0f} | "
              f"{contact.ROW_CARRY * np.ptp(stroke) * 1e6:.0f} | {np.ptp(pred) * 1e6:.0f} | "
              f"{np.corrcoef(pred, d)[0, 1]:.3f} |", flush=True)


if __name__ == "__main__":
    main()
