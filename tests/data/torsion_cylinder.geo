// Circular cylinder R = 1, L = 2 along z, trilinear hexahedra: a quad disk
// (recombined) extruded in 6 layers (tests/prescribed_rotation.rs, torsion).
// gmsh -3 torsion_cylinder.geo -format msh41 -o torsion_cylinder.msh
SetFactory("Built-in");
lc = 0.2;
Point(1) = {0, 0, 0, lc};
Point(2) = {1, 0, 0, lc};
Point(3) = {0, 1, 0, lc};
Point(4) = {-1, 0, 0, lc};
Point(5) = {0, -1, 0, lc};
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Circle(3) = {4, 1, 5};
Circle(4) = {5, 1, 2};
Transfinite Curve{1:4} = 9;
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Recombine Surface{1};
Mesh.Algorithm = 6;
Mesh.RecombinationAlgorithm = 1;
out[] = Extrude {0, 0, 2} { Surface{1}; Layers{6}; Recombine; };
Physical Volume("body") = {out[1]};
Physical Surface("bottom") = {1};
Physical Surface("top") = {out[0]};
