# tests/data/tube-sector/tube.py: a quarter of a thick tube a = 10 <= r <= b = 25 mm,
# 0 <= y <= 4 mm (axis along y), 20-node hexahedra: the (r, y) rectangle swept
# about the y axis through 90 degrees (x >= 0, z >= 0). Gmsh 4.15's Python package:
#   python3 tube.py       (writes mesh.msh beside it)
import math
import gmsh

a, b, h = 10.0, 25.0, 4.0
nr, ny, nt = 8, 2, 12
gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
geo = gmsh.model.geo
p = [geo.addPoint(a, 0, 0), geo.addPoint(b, 0, 0), geo.addPoint(b, h, 0), geo.addPoint(a, h, 0)]
l = [geo.addLine(p[i], p[(i + 1) % 4]) for i in range(4)]
loop = geo.addCurveLoop(l)
s = geo.addPlaneSurface([loop])
geo.mesh.setTransfiniteCurve(l[0], nr + 1, "Progression", 1.15)
geo.mesh.setTransfiniteCurve(l[2], nr + 1, "Progression", 1 / 1.15)
geo.mesh.setTransfiniteCurve(l[1], ny + 1)
geo.mesh.setTransfiniteCurve(l[3], ny + 1)
geo.mesh.setTransfiniteSurface(s)
geo.mesh.setRecombine(2, s)
# about the y axis through -90 degrees takes +x to +z
out = geo.revolve([(2, s)], 0, 0, 0, 0, 1, 0, -math.pi / 2, numElements=[nt], recombine=True)
geo.synchronize()
vol = [t for (d, t) in out if d == 3]
gmsh.model.addPhysicalGroup(3, vol, name="tube")
names = {}
for (d, t) in gmsh.model.getBoundary([(3, v) for v in vol], oriented=False):
    xs = gmsh.model.getBoundingBox(2, t)
    lo, hi = xs[:3], xs[3:]
    if hi[1] - lo[1] < 1e-9:
        key = "tube.bottom" if abs(lo[1]) < 1e-9 else "tube.top"
    elif hi[2] - lo[2] < 1e-9:
        key = "tube.z0"
    elif hi[0] - lo[0] < 1e-9:
        key = "tube.x0"
    elif max(hi[0], hi[2]) < a + 1e-6:
        key = "tube.bore"
    else:
        key = "tube.outer"
    names.setdefault(key, []).append(t)
for key, tags in names.items():
    gmsh.model.addPhysicalGroup(2, tags, name=key)
gmsh.option.setNumber("Mesh.ElementOrder", 2)
gmsh.option.setNumber("Mesh.SecondOrderIncomplete", 1)
gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
gmsh.model.mesh.generate(3)
gmsh.write("mesh.msh")
print(sorted(names))
gmsh.finalize()
