#!/usr/bin/env python3
"""Contact pressure of the stiff and the rough hertz-cylinder runs beside Hertz's
p0 sqrt(1 - x^2/a^2) at each run's own load: profiles.svg and profiles.csv.

    asperity run cases/hertz-cylinder --out out/hertz
    asperity run cases/hertz-cylinder/rough.toml --out out/hertz-rough
    python3 cases/hertz-cylinder/profiles.py out/hertz out/hertz-rough cases/hertz-cylinder

Standard library only. Hertz (Johnson 1985, eq. 4.43-4.45), equal bodies in plane
strain: 1/E* = 2(1 - nu^2)/E, a = sqrt(4 P R / (pi E*)), p0 = 2 P / (pi a); P is
twice the joint's normal force (a half model).
"""
import csv
import math
import os
import sys

E, NU, R = 206000.0, 0.3, 50.0


def run(folder):
    joints = list(csv.DictReader(open(os.path.join(folder, "joints.csv"))))
    load = 2.0 * float(joints[-1]["normal_force_n"])
    files = sorted(os.listdir(os.path.join(folder, "interface")))
    rows = csv.DictReader(open(os.path.join(folder, "interface", files[-1])))
    pts = sorted((float(r["x_mm"]), float(r["p_n_mpa"])) for r in rows)
    return load, pts


def hertz(load):
    e_star = E / (2.0 * (1.0 - NU * NU))
    a = math.sqrt(4.0 * load * R / (math.pi * e_star))
    return a, 2.0 * load / (math.pi * a)


def main():
    stiff_dir, rough_dir, out = sys.argv[1:4]
    runs = [("stiff interface (FE)", "#1f4e9c") + run(stiff_dir),
            ("rough interface, c_N = 0.001, m = 0.5 (FE)", "#c0392b") + run(rough_dir)]
    xmax, pmax = 3.0, 1400.0
    w, h, m = 640, 400, 60
    sx = lambda x: m + (w - 2 * m) * x / xmax
    sy = lambda p: h - m - (h - 2 * m) * p / pmax
    svg = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" font-family="sans-serif" font-size="12">',
           f'<rect width="{w}" height="{h}" fill="white"/>',
           f'<line x1="{m}" y1="{h - m}" x2="{w - m}" y2="{h - m}" stroke="black"/>',
           f'<line x1="{m}" y1="{m}" x2="{m}" y2="{h - m}" stroke="black"/>']
    for i in range(7):
        x = 0.5 * i
        svg.append(f'<text x="{sx(x):.1f}" y="{h - m + 16}" text-anchor="middle">{x:g}</text>')
    for i in range(8):
        p = 200.0 * i
        svg.append(f'<text x="{m - 6}" y="{sy(p) + 4:.1f}" text-anchor="end">{p:g}</text>')
    svg.append(f'<text x="{w / 2}" y="{h - 18}" text-anchor="middle">x (mm)</text>')
    svg.append(f'<text x="16" y="{h / 2}" text-anchor="middle" transform="rotate(-90 16 {h / 2})">contact pressure (MPa)</text>')
    table = []
    for k, (label, color, load, pts) in enumerate(runs):
        a, p0 = hertz(load)
        curve = [(x, p0 * math.sqrt(max(0.0, 1.0 - x * x / (a * a)))) for x in
                 [xmax * i / 400 for i in range(401)]]
        path = " ".join(f"{sx(x):.1f},{sy(p):.1f}" for x, p in curve)
        svg.append(f'<polyline points="{path}" fill="none" stroke="{color}" stroke-dasharray="5,4"/>')
        fe = " ".join(f"{sx(x):.1f},{sy(p):.1f}" for x, p in pts if x <= xmax)
        svg.append(f'<polyline points="{fe}" fill="none" stroke="{color}" stroke-width="2"/>')
        y = m + 16 + 32 * k
        svg.append(f'<line x1="{w - m - 250}" y1="{y}" x2="{w - m - 225}" y2="{y}" stroke="{color}" stroke-width="2"/>')
        svg.append(f'<text x="{w - m - 220}" y="{y + 4}" font-size="11">{label}</text>')
        svg.append(f'<line x1="{w - m - 250}" y1="{y + 14}" x2="{w - m - 225}" y2="{y + 14}" stroke="{color}" stroke-dasharray="5,4"/>')
        svg.append(f'<text x="{w - m - 220}" y="{y + 18}" font-size="11">Hertz (rigid limit) at P = {load:.0f} N/mm</text>')
        table += [(label, x, p, p0 * math.sqrt(max(0.0, 1.0 - x * x / (a * a)))) for x, p in pts]
    svg.append("</svg>")
    with open(os.path.join(out, "profiles.svg"), "w") as f:
        f.write("\n".join(svg) + "\n")
    with open(os.path.join(out, "profiles.csv"), "w") as f:
        f.write("run,x_mm,p_fe_mpa,p_hertz_mpa\n")
        for label, x, p, ph in table:
            f.write(f'"{label}",{x:.6f},{p:.6e},{ph:.6e}\n')


if __name__ == "__main__":
    main()
