# tests/data/sphere-octant/sphere.py: an octant (x, y, z >= 0) of a thick
# spherical shell a = 10 <= r <= b = 20 mm, 20-node hexahedra. The octant is
# three blocks, one about each axis (a cubed sphere: the octant's spherical
# triangle cut into three quadrilaterals meeting at its centre (1, 1, 1)/sqrt(3)),
# each swept from the bore to the outer sphere; structured (transfinite) in
# every direction: nt elements along each side of a patch, nr through the wall,
# every node on the sphere of its layer.
# Gmsh 4.15's Python package:
#   python3 sphere.py       (writes mesh.msh beside it)
import math
import gmsh

a, b = 10.0, 20.0
nt, nr = 4, 8
gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
geo = gmsh.model.geo
origin = geo.addPoint(0, 0, 0)
s2, s3 = 1 / math.sqrt(2), 1 / math.sqrt(3)
# the seven points of the octant's triangle on the unit sphere
dirs = {
    "x": (1, 0, 0), "y": (0, 1, 0), "z": (0, 0, 1),
    "xy": (s2, s2, 0), "yz": (0, s2, s2), "zx": (s2, 0, s2),
    "c": (s3, s3, s3),
}
pt = {(k, r): geo.addPoint(*(r * v for v in d)) for k, d in dirs.items() for r in (a, b)}
# great-circle arcs (centre at the origin) between neighbouring points
pairs = [("x", "xy"), ("xy", "y"), ("y", "yz"), ("yz", "z"), ("z", "zx"), ("zx", "x"),
         ("xy", "c"), ("yz", "c"), ("zx", "c")]
arc = {}
for p, q in pairs:
    for r in (a, b):
        arc[(p, q, r)] = geo.addCircleArc(pt[(p, r)], origin, pt[(q, r)])
        geo.mesh.setTransfiniteCurve(arc[(p, q, r)], nt + 1)
radial = {}
for k in dirs:
    radial[k] = geo.addLine(pt[(k, a)], pt[(k, b)])
    geo.mesh.setTransfiniteCurve(radial[k], nr + 1)


def edge(p, q, r):
    """The arc from p to q on radius r, signed by its direction."""
    return arc[(p, q, r)] if (p, q, r) in arc else -arc[(q, p, r)]


# each block's patch: its corners in order around it
patches = {"x": ["x", "xy", "c", "zx"], "y": ["y", "yz", "c", "xy"], "z": ["z", "zx", "c", "yz"]}
sphere = {}
for k, cs in patches.items():
    for r in (a, b):
        loop = geo.addCurveLoop([edge(cs[i], cs[(i + 1) % 4], r) for i in range(4)])
        s = geo.addSurfaceFilling([loop], sphereCenterTag=origin)
        geo.mesh.setTransfiniteSurface(s)
        geo.mesh.setRecombine(2, s)
        sphere[(k, r)] = s
# the plane faces through the wall, one per arc (shared between blocks inside)
side = {}
for p, q in pairs:
    loop = geo.addCurveLoop([edge(p, q, a), radial[q], -edge(p, q, b), -radial[p]])
    s = geo.addPlaneSurface([loop])
    geo.mesh.setTransfiniteSurface(s)
    geo.mesh.setRecombine(2, s)
    side[frozenset((p, q))] = s
vols = []
for k, cs in patches.items():
    faces = [sphere[(k, a)], sphere[(k, b)]]
    faces += [side[frozenset((cs[i], cs[(i + 1) % 4]))] for i in range(4)]
    v = geo.addVolume([geo.addSurfaceLoop(faces)])
    geo.mesh.setTransfiniteVolume(v)
    geo.mesh.setRecombine(3, v)
    vols.append(v)
geo.synchronize()
gmsh.model.addPhysicalGroup(3, vols, name="sphere")
groups = {
    "sphere.bore": [sphere[(k, a)] for k in patches],
    "sphere.outer": [sphere[(k, b)] for k in patches],
    # the symmetry planes: x = 0 holds the arcs y-yz-z, y = 0 z-zx-x, z = 0 x-xy-y
    "sphere.x0": [side[frozenset(("y", "yz"))], side[frozenset(("yz", "z"))]],
    "sphere.y0": [side[frozenset(("z", "zx"))], side[frozenset(("zx", "x"))]],
    "sphere.z0": [side[frozenset(("x", "xy"))], side[frozenset(("xy", "y"))]],
}
for name, tags in groups.items():
    gmsh.model.addPhysicalGroup(2, tags, name=name)
gmsh.option.setNumber("Mesh.ElementOrder", 2)
gmsh.option.setNumber("Mesh.SecondOrderIncomplete", 1)
gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
gmsh.model.mesh.generate(3)
# the transfinite interpolation places the nodes inside a block up to 0.09 mm
# off the sphere of their layer: each node is moved along its radius onto it
# (corner layers a + k (b - a)/nr, midside layers half-way), so that the
# elements are spherical layers
tags, xyz, _ = gmsh.model.mesh.getNodes()
step = (b - a) / (2 * nr)
for i, t in enumerate(tags):
    x = xyz[3 * i: 3 * i + 3]
    r = math.sqrt(sum(v * v for v in x))
    if r == 0:
        continue  # the arcs' centre, in no element (not written)
    layer = a + step * round((r - a) / step)
    assert abs(r - layer) < 0.25 * step, (t, r)
    gmsh.model.mesh.setNode(t, [v * layer / r for v in x], [])
gmsh.write("mesh.msh")
types, tags, _ = gmsh.model.mesh.getElements(3)
print({int(t): len(e) for t, e in zip(types, tags)}, "nodes", len(gmsh.model.mesh.getNodes()[0]))
gmsh.finalize()
