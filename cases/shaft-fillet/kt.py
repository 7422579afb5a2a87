#!/usr/bin/env python3
"""cases/shaft-fillet/kt.py OUT: the numbers of README.md from a run's output folder.

    asperity run cases/shaft-fillet --out OUT && python3 cases/shaft-fillet/kt.py OUT

Reads OUT/summary.json (the support's reaction, the peak von Mises stress) and
OUT/vtu/0001.vtu (ASCII: the case sets vtu_format = "ascii"; nodal stresses rr, zz,
rz, θθ, averaged from the elements' Gauss points). Prints the nominal stress from
the reaction and across the shank, the largest principal stress on the fillet's
surface, the FE K_t, the published K_t of Tipton, Sorem & Rolovic's finite-element
fit and Peterson's from his chart's fitted formula. Standard library only.
"""
import json
import math
import sys
import xml.etree.ElementTree as ET

D_SMALL, D_LARGE, R_FILLET = 10.0, 16.0, 1.0  # d, D, r (mm), as in shaft.geo
CENTRE = (D_SMALL / 2 + R_FILLET, 20.0 - R_FILLET)  # the fillet arc's centre (r, z)
SIGMA_APPLIED = 100.0  # MPa, the case's -100 MPa pressure on the shank end


def peterson_kt(d, big_d, r):
    """Stepped round bar in tension, shoulder fillet: the fitted formula of Peterson's
    chart (Pilkey & Pilkey, 3rd ed., chart 3.4), t = (D - d)/2, valid 0.1 <= t/r <= 20."""
    t = (big_d - d) / 2
    q = t / r
    s = math.sqrt(q)
    if q <= 2.0:
        c = (0.926 + 1.157 * s - 0.099 * q, 0.012 - 3.036 * s + 0.961 * q,
             -0.302 + 3.977 * s - 1.744 * q, 0.365 - 2.098 * s + 0.878 * q)
    else:
        c = (1.200 + 0.860 * s - 0.022 * q, -1.805 - 0.346 * s - 0.038 * q,
             2.198 - 0.486 * s + 0.165 * q, -0.593 - 0.028 * s - 0.106 * q)
    x = 2 * t / big_d
    return c[0] + c[1] * x + c[2] * x**2 + c[3] * x**3


def tipton_kt(d, big_d, r):
    """Stepped round bar in tension, shoulder fillet: Tipton, Sorem & Rolovic's fit of
    their finite-element K_t (ASME J. Mech. Des. 118, 1996, 321-327; constants as
    listed by Tipton, Sorem & Schmidt, Machine Design, 8 Jan. 2009), the largest
    principal stress over 4P/(pi d^2); the same as tests/verification/fillet.rs."""
    k, rho = big_d / d, r / d
    ratio = (3.43 - 3.41 * k**2 - 0.0232 * k**4) / (1 - 8.85 * k**2 - 0.078 * k**4)
    return 0.493 + 0.48 * k**-2.43 + rho**-0.48 * math.sqrt(ratio)


def arrays(path):
    """The VTU's points (r, z) and nodal stress rows."""
    piece = ET.parse(path).getroot().find("UnstructuredGrid/Piece")
    vals = lambda e: [float(v) for v in e.text.split()]
    pts = vals(piece.find("Points/DataArray"))
    points = [(pts[i], pts[i + 1]) for i in range(0, len(pts), 3)]
    for e in piece.find("PointData"):
        if e.get("Name") == "stress":
            s = vals(e)
            return points, [s[i:i + 4] for i in range(0, len(s), 4)]
    raise SystemExit(f"{path}: no stress array")


def main(out):
    summary = json.load(open(f"{out}/summary.json"))
    force = next(g for g in summary["reactions"] if g["set"] == "shaft.top")["final"][0]
    area = math.pi * D_SMALL**2 / 4
    sigma_nom = force / area
    print(f"reaction at the head's end: {force:.6f} N; sigma_nom = F/(pi d^2/4) = {sigma_nom:.6f} MPa "
          f"(applied {SIGMA_APPLIED}: {sigma_nom / SIGMA_APPLIED - 1:+.1e})")

    points, stress = arrays(f"{out}/vtu/0001.vtu")
    # a section of the shank 15 mm from the fillet: the quads' node row nearest z = 5
    z5 = min({round(z, 9) for r, z in points if r <= 5.0 and z < 12.0}, key=lambda z: abs(z - 5.0))
    szz = [s[1] for (r, z), s in zip(points, stress) if abs(z - z5) < 1e-6]
    print(f"sigma_zz across the shank at z = {z5:.3f} mm ({len(szz)} nodes): "
          f"{min(szz):.4f} to {max(szz):.4f} MPa")

    best = None
    for (r, z), (srr, szz_, srz, stt) in zip(points, stress):
        on_arc = abs(math.hypot(r - CENTRE[0], z - CENTRE[1]) - R_FILLET) < 1e-6
        if on_arc and r <= CENTRE[0] + 1e-9 and z >= CENTRE[1] - 1e-9:
            s1 = max((srr + szz_) / 2 + math.hypot((srr - szz_) / 2, srz), stt)
            if best is None or s1 > best[0]:
                best = (s1, r, z)
    s1, r, z = best
    angle = math.degrees(math.atan2(z - CENTRE[1], CENTRE[0] - r))  # 0 at the shank's tangent point
    kt_fe = s1 / sigma_nom
    kt_p = peterson_kt(D_SMALL, D_LARGE, R_FILLET)
    kt_t = tipton_kt(D_SMALL, D_LARGE, R_FILLET)
    vm = summary["peaks"][0]["max_von_mises"]
    print(f"largest principal stress on the fillet (nodal): {s1:.3f} MPa at r = {r:.4f}, z = {z:.4f} mm, "
          f"{angle:.1f} deg up the arc from the shank")
    print(f"largest von Mises stress (Gauss point, summary.json): {vm['value_mpa']:.3f} MPa "
          f"at r = {vm['x_mm']:.4f}, z = {vm['y_mm']:.4f} mm")
    print(f"K_t FE = {kt_fe:.4f}; r/d = {R_FILLET / D_SMALL:g}, D/d = {D_LARGE / D_SMALL:g}: "
          f"Tipton et al. {kt_t:.4f} (FE/Tipton - 1 = {kt_fe / kt_t - 1:+.2%}), "
          f"Peterson chart 3.4 {kt_p:.4f} (FE/Peterson - 1 = {kt_fe / kt_p - 1:+.1%})")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
