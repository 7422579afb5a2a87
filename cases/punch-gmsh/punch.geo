// cases/punch-gmsh/punch.geo: the mesh of cases/punch-plane-stress, built by Gmsh.
//   gmsh punch.geo -2 -o mesh.msh            (ASCII, what the case reads)
//   gmsh punch.geo -2 -bin -o punch-bin.msh  (the same mesh, binary)
// Half model x >= 0. Punch 20 x 20 mm on a 60 x 60 mm foundation; the two bodies
// touch along y = 0 but have their own points and curves there, so each gets its
// own nodes: asperity pairs them ([[mesh.interface]] upper_curve / lower_curve).

Geometry.AutoCoherence = 0;     // do not merge the coincident points at y = 0
Mesh.ElementOrder = 2;          // quadratic elements ...
Mesh.SecondOrderIncomplete = 1; // ... without centre nodes: 8-node serendipity quads
Mesh.MshFileVersion = 4.1;

// asperity's grading: n elements with size ratio last/first = r over a segment, so
// successive elements grow by q = r^(1/(n-1)) along the curve's direction.

// ---- punch (body "punch"): x [0, 20] 8 elements r = 0.2, y [0, 20] 6 elements r = 5
Point(1) = {0, 0, 0};
Point(2) = {20, 0, 0};
Point(3) = {20, 20, 0};
Point(4) = {0, 20, 0};
Line(1) = {1, 2};   // bottom, +x
Line(2) = {2, 3};   // right, +y
Line(3) = {4, 3};   // top, +x
Line(4) = {1, 4};   // left, +y
Curve Loop(1) = {1, 2, -3, -4};
Plane Surface(1) = {1};
Transfinite Curve {1, 3} = 8 + 1 Using Progression 0.2^(1/7);
Transfinite Curve {2, 4} = 6 + 1 Using Progression 5^(1/5);
Transfinite Surface {1} = {1, 2, 3, 4};
Recombine Surface {1};

// ---- foundation (body "foundation"): x [0, 20] 8 r = 0.2 and [20, 60] 8 r = 8,
//      y [-60, 0] 12 elements r = 0.1; two transfinite patches split at x = 20
Point(11) = {0, -60, 0};
Point(12) = {20, -60, 0};
Point(13) = {60, -60, 0};
Point(14) = {60, 0, 0};
Point(15) = {20, 0, 0};
Point(16) = {0, 0, 0};
Line(11) = {11, 12};  // bottom left, +x
Line(12) = {12, 13};  // bottom right, +x
Line(13) = {13, 14};  // right, +y
Line(14) = {16, 15};  // top left, +x
Line(15) = {15, 14};  // top right, +x
Line(16) = {11, 16};  // left, +y
Line(17) = {12, 15};  // x = 20, +y
Curve Loop(2) = {11, 17, -14, -16};
Plane Surface(2) = {2};
Curve Loop(3) = {12, 13, -15, -17};
Plane Surface(3) = {3};
Transfinite Curve {11, 14} = 8 + 1 Using Progression 0.2^(1/7);
Transfinite Curve {12, 15} = 8 + 1 Using Progression 8^(1/7);
Transfinite Curve {16, 17, 13} = 12 + 1 Using Progression 0.1^(1/11);
Transfinite Surface {2} = {11, 12, 15, 16};
Transfinite Surface {3} = {12, 13, 14, 15};
Recombine Surface {2, 3};

// ---- physical groups: surfaces are bodies, curves are node/edge sets
Physical Surface("punch") = {1};
Physical Surface("foundation") = {2, 3};
Physical Curve("punch.bottom") = {1};
Physical Curve("punch.right") = {2};
Physical Curve("punch.top") = {3};
Physical Curve("punch.left") = {4};
Physical Curve("foundation.bottom") = {11, 12};
Physical Curve("foundation.right") = {13};
Physical Curve("foundation.top") = {14, 15};
Physical Curve("foundation.left") = {16};
