#!/usr/bin/env python3
"""One 30° sector of a bolted pipe flange (12 bolts), 20-node hexahedra, as a
Gmsh MSH 4.1 ASCII mesh on standard output.

    python3 flange.py > flange.msh            # the shipped coarse mesh
    python3 flange.py --refine 5 > big.msh    # the benchmark mesh (> 300k dofs)
    python3 flange.py --check [--refine K]    # the mesh's own checks (see below)

Two identical flanges bolted face to face, the joint plane y = 0, the pipe
axis the y axis; the sector spans θ = −15° … +15° (x = r cos θ, z = r sin θ,
the angle `revolve` and `[model] cyclic` use) with its bolt on θ = 0:

* `upper`: the flange ring 50 ≤ r ≤ 110, 0 ≤ y ≤ 16, with a clearance hole of
  radius 8.75 about (85, y, 0), and the pipe stub 50 ≤ r ≤ 56, 16 ≤ y ≤ 56;
  `lower` is its mirror image in y = 0 (its own nodes, none shared).
* `bolt`: an M16 bolt, its shank of the stress cross-section
  A_s = 157 mm² (radius 7.069) from y = −16 to 16, a head disc of radius 12
  on 16 ≤ y ≤ 26 and a nut disc on −26 ≤ y ≤ −16 (the thread's stiffness
  lumped into the nut's disc). The shank does not touch the hole.

The mesh is a plane mesh of 8-node quadrilaterals in (x, z), one per body,
extruded along y. Around the hole an O-grid: concentric rings from the hole
(8.75) to the washer radius r_w = 12, so that the head's and nut's bearing
annuli have the flange's nodes, then blended linearly to the outline of the
hole block 63 ≤ r ≤ 110 (its sides: the arcs r = 63 and r = 110, the cut
faces θ = ±15°); the ring 50 … 63 is mapped in (r, θ), with a node circle
at r = 56 where the stub stands. The bolt is an O-grid disc: a square core,
a ring out to the shank's circle, then in the head and the nut the rings to
8.75 and 12 with the flange's angles. Every node, midsides included, is
placed by the map of its block (the arcs' nodes lie on the arcs), and the cut
faces' nodes are the same radii on θ = −15° and θ = +15°.

Physical volumes: upper, lower, bolt. Physical surfaces (8-node quads):
sector.theta0 (θ = −15°) and sector.theta1 (θ = +15°), the cut faces of both
flanges (the bolt has none); per flange <flange>.end (the stub's end),
.bore (r = 50), .outside (r = 110), .joint_bolt (the annulus 8.75 … 12
about the hole on y = 0, under the washer circle) and .joint (the rest of the
face on y = 0), .bearing (the annulus under the head / nut), .hole (the
hole's wall);
bolt.head_bearing and bolt.nut_bearing (the annuli against the flanges).

`--check` integrates every element's volume by its 3 × 3 × 3 Gauss rule
(exact for these elements), refuses a Jacobian ≤ 0 at a Gauss point,
compares each body's volume with the closed form of the geometry the
quadratic elements represent (every arc replaced by the parabola through its
three nodes: a segment of angle Δ on radius R loses or gains
R²[(a − sin a cos a) − 4/3 sin a (1 − cos a)], a = Δ/2) to 1e-9 and prints
the difference from the true geometry's volume (it falls as the fourth power
of the element angle), and checks that the θ = −15° face turned by +30° about
y lands on the θ = +15° face node for node.
"""

import argparse
import math
import sys

# ---------------------------------------------------------------- geometry, mm
SECTORS = 12
HALF = math.pi / SECTORS  # the half angle of the sector, 15°
R_BORE, R_STUB, R_BLOCK, R_OUT = 50.0, 56.0, 63.0, 110.0
R_BOLT = 85.0  # the bolt circle's radius
T_FLANGE = 16.0  # each flange's thickness
L_STUB = 40.0  # the stub beyond the flange
R_HOLE = 8.75  # the clearance hole (M16, medium)
R_SHANK = math.sqrt(157.0 / math.pi)  # the stress cross-section A_s = 157 mm²
R_WASHER = 12.0  # the head's and nut's bearing radius
H_HEAD = 10.0  # the head's and nut's height
CORE = 0.45  # the bolt core square's half side / R_SHANK

TOL = 1e-7  # coincident points, mm


class Plane:
    """A plane mesh of 8-node quadrilaterals in (x, z): nodes merged by
    position, each quad with a region tag."""

    def __init__(self):
        self.xz = []
        self.cells = {}
        self.quads = []  # ([c0, c1, c2, c3, m01, m12, m23, m30], region)

    def node(self, p):
        key = (round(p[0] / 1e-6), round(p[1] / 1e-6))
        for dx in (-1, 0, 1):
            for dz in (-1, 0, 1):
                for n in self.cells.get((key[0] + dx, key[1] + dz), ()):
                    q = self.xz[n]
                    if abs(q[0] - p[0]) < TOL and abs(q[1] - p[1]) < TOL:
                        return n
        self.xz.append((p[0], p[1]))
        self.cells.setdefault(key, []).append(len(self.xz) - 1)
        return len(self.xz) - 1

    def patch(self, f, ns, nt, region):
        """The map f(s, t) -> (x, z) on [0, 1]² cut into ns × nt quads, every
        node (corners and midsides) placed by the map."""
        for i in range(ns):
            s0, s1 = i / ns, (i + 1) / ns
            sm = 0.5 * (s0 + s1)
            for j in range(nt):
                t0, t1 = j / nt, (j + 1) / nt
                tm = 0.5 * (t0 + t1)
                pts = [f(s0, t0), f(s1, t0), f(s1, t1), f(s0, t1),
                       f(sm, t0), f(s1, tm), f(sm, t1), f(s0, tm)]
                q = [self.node(p) for p in pts]
                # corners turning about +y: (c1 − c0) × (c3 − c0) along +y
                a = [self.xz[q[1]][k] - self.xz[q[0]][k] for k in (0, 1)]
                b = [self.xz[q[3]][k] - self.xz[q[0]][k] for k in (0, 1)]
                if a[1] * b[0] - a[0] * b[1] < 0.0:
                    q = [q[0], q[3], q[2], q[1], q[7], q[6], q[5], q[4]]
                self.quads.append((q, region))

    def boundary_edges(self):
        """Edges [end, mid, end] that bound one quad only, with its region."""
        count = {}
        for q, region in self.quads:
            for k in range(4):
                e = (q[k], q[4 + k], q[(k + 1) % 4])
                key = (min(e[0], e[2]), max(e[0], e[2]))
                count.setdefault(key, []).append((e, region))
        return [v[0] for v in count.values() if len(v) == 1]


def polar(r, th):
    return (r * math.cos(th), r * math.sin(th))


def hole_point(rho, phi):
    return (R_BOLT + rho * math.cos(phi), rho * math.sin(phi))


def outline(side, s):
    """The hole block's outline, counter-clockwise about the hole seen from
    +z to +x (the local angle φ): side 0 the arc r = 110, 1 the cut face
    θ = +15°, 2 the arc r = 63, 3 the cut face θ = −15°."""
    if side == 0:
        return polar(R_OUT, -HALF + 2.0 * HALF * s)
    if side == 1:
        return polar(R_OUT - (R_OUT - R_BLOCK) * s, HALF)
    if side == 2:
        return polar(R_BLOCK, HALF - 2.0 * HALF * s)
    return polar(R_BLOCK + (R_OUT - R_BLOCK) * s, -HALF)


def side_angle(side, s):
    return math.radians(-45.0 + 90.0 * (side + s))


def flange_plane(k):
    """The flange's plane mesh: regions 'ring' (50 … 56, under the stub),
    'inner' (56 … 63), 'bearing' (the annulus 8.75 … 12 about the hole) and
    'blend' (12 … the hole block's outline)."""
    ns, nw, nb = 2 * k, k, 2 * k
    m = Plane()
    m.patch(lambda s, t: polar(R_BORE + (R_STUB - R_BORE) * t, -HALF + 2 * HALF * s), ns, k, "ring")
    m.patch(lambda s, t: polar(R_STUB + (R_BLOCK - R_STUB) * t, -HALF + 2 * HALF * s), ns, k, "inner")
    for side in range(4):
        m.patch(lambda s, t, side=side: hole_point(R_HOLE + (R_WASHER - R_HOLE) * t, side_angle(side, s)),
                ns, nw, "bearing")

        def blend(s, t, side=side):
            c = hole_point(R_WASHER, side_angle(side, s))
            o = outline(side, s)
            return ((1 - t) * c[0] + t * o[0], (1 - t) * c[1] + t * o[1])

        m.patch(blend, ns, nb, "blend")
    return m


def bolt_plane(k):
    """The bolt's plane mesh: 'core' (the square), 'shank' (the ring out to
    the shank's circle), 'overhang' (to the hole's radius) and 'bearing'
    (to the washer radius)."""
    ns = 2 * k
    c = CORE * R_SHANK
    m = Plane()
    m.patch(lambda s, t: (R_BOLT - c + 2 * c * s, -c + 2 * c * t), ns, ns, "core")

    def square(side, s):
        u = [(c, -c + 2 * c * s), (c - 2 * c * s, c), (-c, c - 2 * c * s), (-c + 2 * c * s, -c)][side]
        return (R_BOLT + u[0], u[1])

    for side in range(4):
        def ring(s, t, side=side):
            a = square(side, s)
            b = hole_point(R_SHANK, side_angle(side, s))
            return ((1 - t) * a[0] + t * b[0], (1 - t) * a[1] + t * b[1])

        m.patch(ring, ns, k, "shank")
        m.patch(lambda s, t, side=side: hole_point(R_SHANK + (R_HOLE - R_SHANK) * t, side_angle(side, s)),
                ns, k, "overhang")
        m.patch(lambda s, t, side=side: hole_point(R_HOLE + (R_WASHER - R_HOLE) * t, side_angle(side, s)),
                ns, k, "bearing")
    return m


class Body:
    """A body: its plane mesh's quads extruded along y over layers."""

    def __init__(self, name, plane):
        self.name, self.plane = name, plane
        self.ids = {}  # (plane node, y) -> index into nodes
        self.nodes = []
        self.hexes = []  # 20 nodes, this code's (the solver's) local order
        self.faces = {}  # face set name -> [8 nodes]

    def node(self, n2, y):
        key = (n2, round(y * 1e6))
        if key not in self.ids:
            x, z = self.plane.xz[n2]
            self.ids[key] = len(self.nodes)
            self.nodes.append((x, y, z))
        return self.ids[key]

    def extrude(self, regions, ys, counts):
        """Every quad of the regions swept through the layers: the
        breakpoints ys, counts layers between each two."""
        levels = []
        for a, b, n in zip(ys, ys[1:], counts):
            levels += [(a + (b - a) * i / n, a + (b - a) * (i + 1) / n) for i in range(n)]
        for q, region in self.plane.quads:
            if region not in regions:
                continue
            for y0, y1 in levels:
                ym = 0.5 * (y0 + y1)
                h = [self.node(q[i], y0) for i in range(4)]
                h += [self.node(q[i], y1) for i in range(4)]
                h += [self.node(q[4 + i], y0) for i in range(4)]
                h += [self.node(q[4 + i], y1) for i in range(4)]
                h += [self.node(q[i], ym) for i in range(4)]
                self.hexes.append(h)

    def cap(self, name, regions, y):
        """The face set of the quads of the regions at the level y."""
        out = self.faces.setdefault(name, [])
        for q, region in self.plane.quads:
            if region in regions:
                out.append([self.node(q[i], y) for i in range(8)])

    def side(self, name, on_edge, regions, ys, counts):
        """The face set of the boundary edges of the regions for which
        on_edge(points) holds, swept through the layers of ys (as `extrude`)."""
        out = self.faces.setdefault(name, [])
        for (a, mid, b), region in self.plane.boundary_edges():
            if region not in regions or not on_edge([self.plane.xz[n] for n in (a, mid, b)]):
                continue
            for y0, y1, n in zip(ys, ys[1:], counts):
                for i in range(n):
                    lo, hi = y0 + (y1 - y0) * i / n, y0 + (y1 - y0) * (i + 1) / n
                    ym = 0.5 * (lo + hi)
                    out.append([self.node(a, lo), self.node(b, lo), self.node(b, hi), self.node(a, hi),
                                self.node(mid, lo), self.node(b, ym), self.node(mid, hi), self.node(a, ym)])


def on_radius(r):
    return lambda pts: all(abs(math.hypot(*p) - r) < 1e-6 for p in pts)


def on_angle(th):
    return lambda pts: all(abs(math.atan2(p[1], p[0]) - th) < 1e-9 for p in pts)


def on_hole(pts):
    return all(abs(math.hypot(p[0] - R_BOLT, p[1]) - R_HOLE) < 1e-6 for p in pts)


def flange(name, sign, plane, k):
    """A flange with its stub: sign +1 above the joint plane, −1 below."""
    body = Body(name, plane)
    everything = ("ring", "inner", "bearing", "blend")

    def span(a, b):  # breakpoints increasing in y
        return (a, b) if a < b else (b, a)

    f0, f1 = span(0.0, sign * T_FLANGE)
    s0, s1 = span(sign * T_FLANGE, sign * (T_FLANGE + L_STUB))
    body.extrude(everything, [f0, f1], [2 * k])
    body.extrude(("ring",), [s0, s1], [3 * k])
    for setname, th in (("theta0", -HALF), ("theta1", HALF)):
        body.side(f"sector.{setname}", on_angle(th), everything, [f0, f1], [2 * k])
        body.side(f"sector.{setname}", on_angle(th), ("ring",), [s0, s1], [3 * k])
    body.side(f"{name}.bore", on_radius(R_BORE), everything, [f0, f1], [2 * k])
    body.side(f"{name}.bore", on_radius(R_BORE), ("ring",), [s0, s1], [3 * k])
    body.side(f"{name}.outside", on_radius(R_OUT), everything, [f0, f1], [2 * k])
    body.side(f"{name}.hole", on_hole, everything, [f0, f1], [2 * k])
    body.cap(f"{name}.end", ("ring",), sign * (T_FLANGE + L_STUB))
    body.cap(f"{name}.joint", ("ring", "inner", "blend"), 0.0)
    body.cap(f"{name}.joint_bolt", ("bearing",), 0.0)
    body.cap(f"{name}.bearing", ("bearing",), sign * T_FLANGE)
    return body


def bolt(plane, k):
    body = Body("bolt", plane)
    top, bot = T_FLANGE + H_HEAD, -T_FLANGE - H_HEAD
    body.extrude(("core", "shank"), [bot, -T_FLANGE, 0.0, T_FLANGE, top], [k, 2 * k, 2 * k, k])
    body.extrude(("overhang", "bearing"), [T_FLANGE, top], [k])
    body.extrude(("overhang", "bearing"), [bot, -T_FLANGE], [k])
    body.cap("bolt.head_bearing", ("bearing",), T_FLANGE)
    body.cap("bolt.nut_bearing", ("bearing",), -T_FLANGE)
    return body


def build(k):
    fp, bp = flange_plane(k), bolt_plane(k)
    return [flange("upper", 1.0, fp, k), flange("lower", -1.0, fp, k), bolt(bp, k)]


# ------------------------------------------------------------- MSH 4.1 output
# Gmsh's node g of a type-17 hexahedron is this code's node GMSH_TO_LOCAL[g]
# (src/physics/element/h20.rs): Gmsh orders the midsides by edge 0–1, 0–3,
# 0–4, 1–2, 1–5, 2–3, 2–6, 3–7, 4–5, 4–7, 5–6, 6–7.
GMSH_TO_LOCAL = [0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 16, 9, 17, 10, 18, 19, 12, 15, 13, 14]


def fmt(v):
    return repr(float(v))


def write_msh(bodies, out):
    base = []  # the first global node tag of each body
    total = 0
    for b in bodies:
        base.append(total)
        total += len(b.nodes)
    # one entity per body and face set, one physical surface per name (the
    # cut faces of both flanges are one physical surface per side)
    surfaces = [(bi, name) for bi, b in enumerate(bodies) for name in b.faces]
    names = list(dict.fromkeys(name for _, name in surfaces))
    w = out.write
    w("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n")
    w(f"$PhysicalNames\n{len(bodies) + len(names)}\n")
    for t, name in enumerate(names, 1):
        w(f'2 {t} "{name}"\n')
    for t, b in enumerate(bodies, 1):
        w(f'3 {t} "{b.name}"\n')
    w("$EndPhysicalNames\n")

    def bbox(points):
        lo = [min(p[i] for p in points) for i in range(3)]
        hi = [max(p[i] for p in points) for i in range(3)]
        return " ".join(fmt(v) for v in lo + hi)

    w(f"$Entities\n0 0 {len(surfaces)} {len(bodies)}\n")
    for t, (bi, name) in enumerate(surfaces, 1):
        pts = [bodies[bi].nodes[n] for f in bodies[bi].faces[name] for n in f]
        w(f"{t} {bbox(pts)} 1 {names.index(name) + 1} 0\n")
    for t, b in enumerate(bodies, 1):
        w(f"{t} {bbox(b.nodes)} 1 {t} 0\n")
    w("$EndEntities\n")
    w(f"$Nodes\n{len(bodies)} {total} 1 {total}\n")
    for t, b in enumerate(bodies, 1):
        w(f"3 {t} 0 {len(b.nodes)}\n")
        for n in range(len(b.nodes)):
            w(f"{base[t - 1] + n + 1}\n")
        for p in b.nodes:
            w(f"{fmt(p[0])} {fmt(p[1])} {fmt(p[2])}\n")
    w("$EndNodes\n")
    n_el = sum(len(b.hexes) for b in bodies) + sum(len(bodies[bi].faces[nm]) for bi, nm in surfaces)
    w(f"$Elements\n{len(surfaces) + len(bodies)} {n_el} 1 {n_el}\n")
    tag = 1
    for t, (bi, name) in enumerate(surfaces, 1):
        faces = bodies[bi].faces[name]
        w(f"2 {t} 16 {len(faces)}\n")
        for f in faces:
            w(f"{tag} " + " ".join(str(base[bi] + n + 1) for n in f) + "\n")
            tag += 1
    for t, b in enumerate(bodies, 1):
        w(f"3 {t} 17 {len(b.hexes)}\n")
        for h in b.hexes:
            w(f"{tag} " + " ".join(str(base[t - 1] + h[g] + 1) for g in GMSH_TO_LOCAL) + "\n")
            tag += 1
    w("$EndElements\n")


# ------------------------------------------------------------------- checks
NODE_XI = [(-1, -1, -1), (1, -1, -1), (1, 1, -1), (-1, 1, -1),
           (-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1),
           (0, -1, -1), (1, 0, -1), (0, 1, -1), (-1, 0, -1),
           (0, -1, 1), (1, 0, 1), (0, 1, 1), (-1, 0, 1),
           (-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)]


def h20_derivs(xi):
    """∂N/∂(ξ, η, ζ) of the 20-node serendipity hexahedron (corners:
    N = (1+ξξₐ)(1+ηηₐ)(1+ζζₐ)(ξξₐ+ηηₐ+ζζₐ−2)/8; midsides with ξₐ = 0:
    N = (1−ξ²)(1+ηηₐ)(1+ζζₐ)/4, and alike)."""
    out = []
    for xa in NODE_XI:
        f = [1 + xi[i] * xa[i] for i in range(3)]
        zero = [i for i in range(3) if xa[i] == 0]
        d = [0.0, 0.0, 0.0]
        if not zero:
            s = sum(xi[i] * xa[i] for i in range(3)) - 2
            for i in range(3):
                j, k = (i + 1) % 3, (i + 2) % 3
                d[i] = xa[i] * f[j] * f[k] * (s + f[i]) / 8
        else:
            z = zero[0]
            j, k = (z + 1) % 3, (z + 2) % 3
            g = 1 - xi[z] ** 2
            d[z] = -2 * xi[z] * f[j] * f[k] / 4
            d[j] = g * xa[j] * f[k] / 4
            d[k] = g * f[j] * xa[k] / 4
        out.append(d)
    return out


GAUSS3 = [(-math.sqrt(0.6), 5 / 9), (0.0, 8 / 9), (math.sqrt(0.6), 5 / 9)]
RULE = [((a, b, c), wa * wb * wc) for a, wa in GAUSS3 for b, wb in GAUSS3 for c, wc in GAUSS3]
DERIVS = [(h20_derivs(p), w) for p, w in RULE]


def volume(body):
    """Σ det J w over every element; raises on a Jacobian ≤ 0."""
    total = 0.0
    for e, h in enumerate(body.hexes):
        x = [body.nodes[n] for n in h]
        for d, w in DERIVS:
            j = [[sum(d[a][c] * x[a][r] for a in range(20)) for c in range(3)] for r in range(3)]
            det = (j[0][0] * (j[1][1] * j[2][2] - j[1][2] * j[2][1])
                   - j[0][1] * (j[1][0] * j[2][2] - j[1][2] * j[2][0])
                   + j[0][2] * (j[1][0] * j[2][1] - j[1][1] * j[2][0]))
            if det <= 0.0:
                raise SystemExit(f"{body.name}: element {e} has det J = {det} at a Gauss point")
            total += det * w
    return total


def deficit(r, delta):
    """The area between an arc of radius r and angle delta and the parabola
    through its ends and its midpoint."""
    a = delta / 2
    return r * r * ((a - math.sin(a) * math.cos(a)) - 4.0 / 3.0 * math.sin(a) * (1 - math.cos(a)))


def volumes(k):
    """Each body's volume: the true geometry's and the quadratic mesh's
    closed form (convex arcs lose their deficit, concave ones gain it)."""
    ns = 2 * k
    sector = 2 * HALF
    hole_arcs = 4 * ns * deficit(R_HOLE, math.pi / 2 / ns)
    flange_true = (0.5 * sector * (R_OUT ** 2 - R_BORE ** 2) - math.pi * R_HOLE ** 2) * T_FLANGE \
        + 0.5 * sector * (R_STUB ** 2 - R_BORE ** 2) * L_STUB
    d = sector / ns
    flange_quad = flange_true + hole_arcs * T_FLANGE \
        - ns * deficit(R_OUT, d) * T_FLANGE \
        + ns * deficit(R_BORE, d) * (T_FLANGE + L_STUB) \
        - ns * deficit(R_STUB, d) * L_STUB
    shank, washer = 2 * T_FLANGE, 2 * H_HEAD
    bolt_true = math.pi * (R_SHANK ** 2 * shank + R_WASHER ** 2 * washer)
    bolt_quad = bolt_true - 4 * ns * (deficit(R_SHANK, math.pi / 2 / ns) * shank
                                      + deficit(R_WASHER, math.pi / 2 / ns) * washer)
    return {"upper": (flange_true, flange_quad), "lower": (flange_true, flange_quad),
            "bolt": (bolt_true, bolt_quad)}


def check(bodies, k):
    ok = True
    want = volumes(k)
    for b in bodies:
        v = volume(b)
        true, quad = want[b.name]
        rel_q, rel_t = abs(v - quad) / quad, abs(v - true) / true
        print(f"{b.name}: {len(b.hexes)} elements, {len(b.nodes)} nodes; volume {v:.9f} mm³, "
              f"parabolic arcs' closed form {quad:.9f} (rel. {rel_q:.1e}), "
              f"true geometry {true:.9f} (rel. {rel_t:.1e})")
        ok &= rel_q < 1e-9
    turn = 2 * HALF
    for b in bodies:
        if "sector.theta0" not in b.faces:
            continue
        n0 = sorted({n for f in b.faces["sector.theta0"] for n in f})
        n1 = sorted({n for f in b.faces["sector.theta1"] for n in f})
        target = {}
        for n in n1:
            x, y, z = b.nodes[n]
            target[(round(x, 6), round(y, 6), round(z, 6))] = n
        hit, worst = set(), 0.0
        for n in n0:
            x, y, z = b.nodes[n]
            p = (x * math.cos(turn) - z * math.sin(turn), y, x * math.sin(turn) + z * math.cos(turn))
            m = target.get(tuple(round(c, 6) for c in p))
            if m is None:
                ok = False
                print(f"{b.name}: node at {b.nodes[n]} turned by 30° meets no node of theta1")
                continue
            hit.add(m)
            worst = max(worst, max(abs(p[i] - b.nodes[m][i]) for i in range(3)))
        ok &= len(hit) == len(n1) == len(n0)
        print(f"{b.name}: theta0 turned by +30° about y onto theta1: {len(hit)} of {len(n1)} nodes, "
              f"largest miss {worst:.1e} mm")
    dofs = 3 * sum(len(b.nodes) for b in bodies)
    print(f"total: {sum(len(b.hexes) for b in bodies)} elements, {dofs} dofs")
    if not ok:
        raise SystemExit("flange.py --check: FAILED")
    print("flange.py --check: ok")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--refine", type=int, default=1, help="refinement factor K >= 1 (default 1)")
    ap.add_argument("--check", action="store_true", help="check the mesh instead of writing it")
    args = ap.parse_args()
    if args.refine < 1:
        ap.error("--refine must be at least 1")
    bodies = build(args.refine)
    if args.check:
        check(bodies, args.refine)
    else:
        write_msh(bodies, sys.stdout)


if __name__ == "__main__":
    main()
