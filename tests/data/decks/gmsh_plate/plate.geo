// A 100 x 50 mm plate of quadrilaterals with a named surface and edges, as a user would mesh
// it with gmsh 4.8 (Debian 12):  gmsh plate.geo -2 -format inp -o plate_mesh.inp
// gmsh writes the quads as CPS4 (it has no shell element names); the wrapper deck gives them
// a *SHELL SECTION.
L = 0.1;
W = 0.05;
Point(1) = {0, 0, 0};
Point(2) = {L, 0, 0};
Point(3) = {L, W, 0};
Point(4) = {0, W, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve {1, 3} = 9;
Transfinite Curve {2, 4} = 5;
Transfinite Surface {1};
Recombine Surface {1};
Physical Surface("plate") = {1};
Physical Curve("clamped") = {4};
Physical Curve("free_edge") = {2};
