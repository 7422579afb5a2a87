// cases/shaft-fillet/shaft.geo: a stepped round bar (shoulder fillet) in tension,
// axisymmetric (x = r, y = z), one body "shaft".
//   gmsh shaft.geo -2 -o mesh.msh      (or, with the Python package:
//   python3 -c "import gmsh; gmsh.initialize(); gmsh.open('shaft.geo'); gmsh.model.mesh.generate(2); gmsh.write('mesh.msh'); gmsh.finalize()")
// Small diameter d = 10 mm (shank, z in [0, 19]), large diameter D = 16 mm
// (shoulder at z = 20, head up to z = 40), fillet radius r = 1 mm from (5, 19)
// to (6, 20) about (6, 19); the shoulder face is flat from r = 6 to r = 8.
// The zone around the fillet (z in [12, 28]) is an unrecombined surface:
// 6-node triangles, graded toward the arc by a distance field. The shank's end
// (z in [0, 12]) and the head's end (z in [28, 40]) are transfinite and
// recombined: 8-node quads. The mesh is mixed in one body.

Mesh.ElementOrder = 2;          // quadratic elements ...
Mesh.SecondOrderIncomplete = 1; // ... without centre nodes: 8-node quads, 6-node triangles
Mesh.MshFileVersion = 4.1;

d = 10.0;   // shank diameter
D = 16.0;   // head (shoulder) diameter
rf = 1.0;   // fillet radius
zs = 20.0;  // shoulder face

Point(1) = {0, 0, 0};
Point(2) = {d/2, 0, 0};
Point(3) = {d/2, 12, 0};
Point(4) = {0, 12, 0};
Point(5) = {d/2, zs - rf, 0};        // fillet start on the shank
Point(6) = {d/2 + rf, zs - rf, 0};   // fillet centre
Point(7) = {d/2 + rf, zs, 0};        // fillet end on the shoulder face
Point(8) = {D/2, zs, 0};
Point(9) = {D/2, 28, 0};
Point(10) = {0, 28, 0};
Point(11) = {D/2, 40, 0};
Point(12) = {0, 40, 0};

Line(1) = {1, 2};         // shank end z = 0 (loaded), +r
Line(2) = {2, 3};         // shank surface, lower part
Line(3) = {4, 3};         // quads / triangles at z = 12, +r
Line(4) = {1, 4};         // axis, lower part
Line(5) = {3, 5};         // shank surface up to the fillet
Circle(6) = {5, 6, 7};    // the fillet
Line(7) = {7, 8};         // shoulder face
Line(8) = {8, 9};         // head surface, lower part
Line(9) = {10, 9};        // triangles / quads at z = 28, +r
Line(10) = {4, 10};       // axis, middle part
Line(11) = {9, 11};       // head surface, upper part
Line(12) = {12, 11};      // head end z = 40 (supported), +r
Line(13) = {10, 12};      // axis, upper part

Curve Loop(1) = {1, 2, -3, -4};
Plane Surface(1) = {1};                    // shank end: quads
Curve Loop(2) = {3, 5, 6, 7, 8, -9, -10};
Plane Surface(2) = {2};                    // fillet zone: triangles
Curve Loop(3) = {9, 11, -12, -13};
Plane Surface(3) = {3};                    // head end: quads

Transfinite Curve {1, 3} = 6 + 1;                        // 0.83 mm across the shank
Transfinite Curve {2, 4} = 8 + 1 Using Progression 0.8^(1/7);  // finer toward z = 12
Transfinite Surface {1} = {1, 2, 3, 4};
Recombine Surface {1};
Transfinite Curve {9, 12} = 8 + 1;                       // 1 mm across the head
Transfinite Curve {11, 13} = 8 + 1 Using Progression 1.5^(1/7);  // coarser toward z = 40
Transfinite Surface {3} = {10, 9, 11, 12};
Recombine Surface {3};

// element size in the triangle zone: 0.06 mm within 0.05 mm of the fillet,
// growing linearly to 0.8 mm at 4 mm from it
Field[1] = Distance;
Field[1].CurvesList = {6};
Field[1].Sampling = 200;
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = 0.06;
Field[2].SizeMax = 0.8;
Field[2].DistMin = 0.05;
Field[2].DistMax = 4.0;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;

Physical Surface("shaft") = {1, 2, 3};
Physical Curve("shaft.bottom") = {1};       // the shank's end: the tension
Physical Curve("shaft.top") = {12};         // the head's end: the support
Physical Curve("shaft.axis") = {4, 10, 13};
Physical Curve("shaft.fillet") = {6};
