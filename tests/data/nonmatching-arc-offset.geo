// tests/data/nonmatching-arc-offset.geo: the bodies of nonmatching-arc.geo (a shallow
// circular arc, radius 25.25 mm, 0.5 mm high over the 10 mm width, the lower body
// convex; body "upper" the slave side, body "lower" the master side), but with an
// offset division of the arc: each quarter of it has 6 slave edges and 4 master
// edges (3 and 2 before every edge is split in two to make all elements
// quadrangles), so only every half quarter is a node of both sides. The straight-sided
// polygons of the two sides' elements then overlap by the sagitta of their chords
// (about 1e-3 mm here), which the overlap check accepts between bodies joined by
// a non-matching interface up to crate::interface::OVERLAP_LIMIT of the element.
//   gmsh nonmatching-arc-offset.geo -2 -o nonmatching-arc-offset.msh      (Gmsh 4.8.4)

Geometry.AutoCoherence = 0;     // keep the coincident points on the arc distinct
Mesh.ElementOrder = 2;          // quadratic elements ...
Mesh.SecondOrderIncomplete = 1; // ... without centre nodes: 8-node serendipity quads
Mesh.RecombineAll = 1;          // quadrangles
Mesh.SubdivisionAlgorithm = 1;  // all quadrangles: every edge split in two
Mesh.Algorithm = 6;             // frontal-Delaunay (8, for quads, crashes Gmsh 4.8.4 here)
Mesh.MshFileVersion = 4.1;

hu = 1.5;   // upper body (slave)
hl = 2.5;   // lower body (master): hu = 0.6 hl
R = 25.25;  // arc radius: y = 0 at x = 0 and 10, y = 0.5 at x = 5
yc = 0.5 - R;
t0 = Asin(5 / R);

// ---- upper: above the arc, top at y = 5
Point(1) = {5 - R * Sin(t0), yc + R * Cos(t0), 0, hu};
Point(2) = {5 - R * Sin(t0 / 2), yc + R * Cos(t0 / 2), 0, hu};
Point(3) = {5, 0.5, 0, hu};
Point(4) = {5 + R * Sin(t0 / 2), yc + R * Cos(t0 / 2), 0, hu};
Point(5) = {5 + R * Sin(t0), yc + R * Cos(t0), 0, hu};
Point(6) = {10, 5, 0, hu};
Point(7) = {0, 5, 0, hu};
Point(8) = {5, yc, 0};      // the arc's centre
Circle(1) = {1, 8, 2};      // bottom pieces: +x, -x, +x, -x
Circle(2) = {3, 8, 2};
Circle(3) = {3, 8, 4};
Circle(4) = {5, 8, 4};
Line(5) = {5, 6};   // right
Line(6) = {6, 7};   // top
Line(7) = {7, 1};   // left
Curve Loop(1) = {1, -2, 3, -4, 5, 6, 7};
Plane Surface(1) = {1};
Transfinite Curve {1, 2, 3, 4} = 4;

// ---- lower: below the arc, bottom at y = -5
Point(11) = {0, -5, 0, hl};
Point(12) = {10, -5, 0, hl};
Point(13) = {5 + R * Sin(t0), yc + R * Cos(t0), 0, hl};
Point(14) = {5 + R * Sin(t0 / 2), yc + R * Cos(t0 / 2), 0, hl};
Point(15) = {5, 0.5, 0, hl};
Point(16) = {5 - R * Sin(t0 / 2), yc + R * Cos(t0 / 2), 0, hl};
Point(17) = {5 - R * Sin(t0), yc + R * Cos(t0), 0, hl};
Point(18) = {5, yc, 0};
Line(11) = {11, 12};  // bottom
Line(12) = {12, 13};  // right
Circle(13) = {13, 18, 14};  // top pieces, -x
Circle(14) = {14, 18, 15};
Circle(15) = {15, 18, 16};
Circle(16) = {16, 18, 17};
Line(17) = {17, 11};  // left
Curve Loop(2) = {11, 12, 13, 14, 15, 16, 17};
Plane Surface(2) = {2};
Transfinite Curve {13, 14, 15, 16} = 3;

// ---- physical groups: surfaces are bodies, curves are node/edge sets
Physical Surface("upper") = {1};
Physical Surface("lower") = {2};
Physical Curve("upper.bottom") = {3, 1, 4, 2};
Physical Curve("upper.right") = {5};
Physical Curve("upper.top") = {6};
Physical Curve("upper.left") = {7};
Physical Curve("lower.bottom") = {11};
Physical Curve("lower.right") = {12};
Physical Curve("lower.top") = {13, 14, 15, 16};
Physical Curve("lower.left") = {17};
