// A 20 x 10 x 10 mm block of hexahedra with named faces and a corner point, as a user would
// mesh it with gmsh 4.8 (Debian 12):  gmsh block.geo -3 -format inp -o block_mesh.inp
// (SaveGroupsOfNodes: a *NSET per physical group too, the only way gmsh writes a point group)
Mesh.SaveGroupsOfNodes = 1;
L = 0.02;
W = 0.01;
H = 0.01;
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
Transfinite Curve {1, 3} = 5;
Transfinite Curve {2, 4} = 3;
Transfinite Surface {1};
Recombine Surface {1};
out[] = Extrude {0, 0, H} { Surface{1}; Layers{2}; Recombine; };
Physical Volume("block") = {out[1]};
Physical Surface("bottom") = {1};
Physical Surface("top") = {out[0]};
Physical Point("corner") = {1};
