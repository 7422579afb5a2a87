# cases/shaft-fillet-3d/shaft.py: a quarter of the stepped round bar of cases/shaft-fillet
# (shank d = 10 mm, head D = 16 mm, shoulder fillet r = 1 mm at y = 20, axis along y),
# 10-node tetrahedra graded toward the fillet. Run with Gmsh's Python package (4.15):
#   python3 shaft.py            (writes mesh.msh beside it)
import math
import sys
import gmsh

h_fillet = float(sys.argv[1]) if len(sys.argv) > 1 else 0.3   # element size at the fillet, mm
h_far = 2.5                                                  # element size far from it, mm

gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
gmsh.model.add("shaft")
occ = gmsh.model.occ
shank = occ.addCylinder(0, 0, 0, 0, 20, 0, 5.0)
head = occ.addCylinder(0, 20, 0, 0, 20, 0, 8.0)
bar, _ = occ.fuse([(3, shank)], [(3, head)])
occ.synchronize()
# the concave edge where the shank meets the shoulder: a circle r = 5 at y = 20
edge = [e for (d, e) in gmsh.model.getEntities(1)
        if abs(gmsh.model.occ.getCenterOfMass(1, e)[1] - 20.0) < 1e-6
        and abs(gmsh.model.occ.getMass(1, e) - 2 * math.pi * 5.0) < 1e-6]
assert len(edge) == 1, edge
filleted = occ.fillet([bar[0][1]], edge, [1.0])
quarter = occ.addBox(0, 0, 0, 10, 40, 10)
part, _ = occ.intersect(filleted, [(3, quarter)])
occ.synchronize()
vol = part[0][1]
gmsh.model.addPhysicalGroup(3, [vol], name="shaft")
for (d, s) in gmsh.model.getBoundary(part, oriented=False):
    c = occ.getCenterOfMass(2, s)
    name = None
    if abs(c[1]) < 1e-6:
        name = "shaft.bottom"
    elif abs(c[1] - 40.0) < 1e-6:
        name = "shaft.top"
    elif abs(c[0]) < 1e-6:
        name = "shaft.x0"
    elif abs(c[2]) < 1e-6:
        name = "shaft.z0"
    if name:
        gmsh.model.addPhysicalGroup(2, [s], name=name)
# finer toward the fillet: a distance field from the fillet surface
fillet = [s for (d, s) in gmsh.model.getBoundary(part, oriented=False)
          if 19.0 < occ.getCenterOfMass(2, s)[1] < 20.0]
f = gmsh.model.mesh.field
dist = f.add("Distance")
f.setNumbers(dist, "SurfacesList", fillet)
thr = f.add("Threshold")
f.setNumber(thr, "InField", dist)
f.setNumber(thr, "SizeMin", h_fillet)
f.setNumber(thr, "SizeMax", h_far)
f.setNumber(thr, "DistMin", 0.5)
f.setNumber(thr, "DistMax", 8.0)
f.setAsBackgroundMesh(thr)
gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
gmsh.option.setNumber("Mesh.ElementOrder", 2)
gmsh.option.setNumber("Mesh.SecondOrderIncomplete", 1)
gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
gmsh.model.mesh.generate(3)
gmsh.write(sys.argv[2] if len(sys.argv) > 2 else "mesh.msh")
gmsh.finalize()
