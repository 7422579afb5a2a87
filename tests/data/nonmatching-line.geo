// tests/data/nonmatching-line.geo: two bodies meshed apart along y = 0, for the
// non-matching interface of a file mesh (matching = false): body "upper"
// (the slave side, finer: element size 1.5, two graded edges per master edge
// along the interface) on body "lower" (the master side, element size 2.5, one
// edge per 2.5 mm along the interface). Unstructured quadrangles; the four
// pieces of the upper body's bottom run in alternating directions and are
// listed out of order in their physical curve (the reader orients and chains
// them from the elements).
//   gmsh nonmatching-line.geo -2 -o nonmatching-line.msh      (Gmsh 4.8.4)

Geometry.AutoCoherence = 0;     // keep the coincident points at y = 0 distinct
Mesh.ElementOrder = 2;          // quadratic elements ...
Mesh.SecondOrderIncomplete = 1; // ... without centre nodes: 8-node serendipity quads
Mesh.RecombineAll = 1;          // quadrangles
Mesh.Algorithm = 6;             // frontal-Delaunay (8, for quads, crashes Gmsh 4.8.4 here)
Mesh.MshFileVersion = 4.1;

hu = 1.5;   // upper body (slave)
hl = 2.5;   // lower body (master): hu = 0.6 hl

// ---- upper: [0, 10] x [0, 5]
Point(1) = {0, 0, 0, hu};
Point(2) = {2.5, 0, 0, hu};
Point(3) = {5, 0, 0, hu};
Point(4) = {7.5, 0, 0, hu};
Point(5) = {10, 0, 0, hu};
Point(6) = {10, 5, 0, hu};
Point(7) = {0, 5, 0, hu};
Line(1) = {1, 2};   // bottom pieces: +x, -x, +x, -x
Line(2) = {3, 2};
Line(3) = {3, 4};
Line(4) = {5, 4};
Line(5) = {5, 6};   // right
Line(6) = {6, 7};   // top
Line(7) = {7, 1};   // left
Curve Loop(1) = {1, -2, 3, -4, 5, 6, 7};
Plane Surface(1) = {1};
// two edges per master edge, graded (a slave node at every master edge end, none at
// the master midsides)
Transfinite Curve {1, 2, 3, 4} = 3 Using Progression 1.5;

// ---- lower: [0, 10] x [-5, 0]
Point(11) = {0, -5, 0, hl};
Point(12) = {10, -5, 0, hl};
Point(13) = {10, 0, 0, hl};
Point(14) = {7.5, 0, 0, hl};
Point(15) = {5, 0, 0, hl};
Point(16) = {2.5, 0, 0, hl};
Point(17) = {0, 0, 0, hl};
Line(11) = {11, 12};  // bottom
Line(12) = {12, 13};  // right
Line(13) = {13, 14};  // top pieces, -x
Line(14) = {14, 15};
Line(15) = {15, 16};
Line(16) = {16, 17};
Line(17) = {17, 11};  // left
Curve Loop(2) = {11, 12, 13, 14, 15, 16, 17};
Plane Surface(2) = {2};
Transfinite Curve {13, 14, 15, 16} = 2;

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
