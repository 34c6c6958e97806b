"""The needle-resolved bearing's checks on the full row (the tests run 12 needles for 0.3 cycles):
two whirl cycles of the paper's scene, 46 needles x 7 spheres, every friction on: the needles'
push on the roller against the groove load, where the load sits, containment in the annulus
and the axial stops, finiteness.  Same criteria as tests/test_needles.py; prints the figures.
Usage: python benchmarks/needle_checks.py   (about 35 s)
"""
import math
import time

import numpy as np

from tripod_model.model import ContactModel
from tripod_model import contact, layout as LY


def main():
    m = ContactModel({"bearing": 2})
    p = m.p
    rn = 0.5 * p["d_needle"]
    inner = p["r_trunnion"] + rn
    outer = m.row_bore_radius() - rn
    err, ang, far = [], [], []
    rho_lo, rho_hi, ax_over, finite = 1.0, 0.0, 0.0, True
    t0 = time.time()
    for _ in range(2000):
        o = m.step(1e-4, p["theta"], p["omega"], p["F_press"])
        ND = m.needle_loads()
        pos = m.needle_positions()
        finite &= bool(np.all(np.isfinite(m.Y))) and all(math.isfinite(v) for v in o.values())
        err.append(abs(ND[:, LY.D_R1].sum() - o["Fx"]) / o["Fx"])
        bore = ND[:, LY.D_BORE]
        psi = np.arctan2(pos[:, 1], pos[:, 0])
        ang.append(math.degrees(math.atan2(np.sum(bore * np.sin(psi)),
                                           np.sum(bore * np.cos(psi)))))
        far.append(np.sum(bore[np.cos(psi) < -0.2]) / np.sum(bore))
        rho_lo = min(rho_lo, np.hypot(pos[:, 0], pos[:, 1]).min())
        # the outer limit from the roller bore's axis (the roller sits off the trunnion's by E, W)
        rho_hi = max(rho_hi, np.hypot(pos[:, 0] - m.Y[LY.Y_E], pos[:, 1] - m.Y[LY.Y_W]).max())
        d = contact.trunnion_axial(m.Y[LY.Y_X], p["theta"], p["s"], p["axial"])
        ax_over = max(ax_over, np.max(np.abs(pos[:, 2] - d)) - p["needle_axial_clearance"])
    err = np.array(err)
    print(f"two whirl cycles, {p['n_needles']} x {p['n_spheres']}: wall {time.time() - t0:.1f} s")
    print(f"needle push vs groove load along the pressing direction: median "
          f"{100 * np.median(err):.3f} %, max {100 * err.max():.3f} %")
    print(f"load-weighted direction of the bore loads: {min(ang):.1f} .. {max(ang):.1f} deg "
          f"from +x (the pressing direction)")
    print(f"far side (cos psi < -0.2) share of the bore load: max {100 * max(far):.2f} %")
    print(f"needle centres: from the trunnion axis at least {rho_lo * 1e3:.5f} mm (contact at "
          f"{inner * 1e3:.5f}), from the bore axis at most {rho_hi * 1e3:.5f} mm (contact at "
          f"{outer * 1e3:.5f})")
    print(f"axial: furthest beyond the stops {ax_over * 1e6:.2f} um (stop play "
          f"{p['needle_axial_clearance'] * 1e3:.2f} mm)")
    print(f"every state and output finite: {finite}")


if __name__ == "__main__":
    main()
