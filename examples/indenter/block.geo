// A quarter of an elastic block [0, 2] × [0, 2] × [−2, 0] (top face z = 0)
// for a rigid spherical indenter touching it at the origin, with linear
// tetrahedra refined under the contact (0.006 within 0.15 of the origin,
// growing to 0.3).
// gmsh -3 block.geo -format msh41 -o block.msh
SetFactory("OpenCASCADE");
L = 2.0;
Box(1) = {0, 0, -L, L, L, L};
Point(100) = {0, 0, 0};
Field[1] = Distance;
Field[1].PointsList = {100};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = 0.006;
Field[2].SizeMax = 0.3;
Field[2].DistMin = 0.15;
Field[2].DistMax = 1.0;
Background Field = 2;
Mesh.CharacteristicLengthFromPoints = 0;
Mesh.CharacteristicLengthExtendFromBoundary = 0;
eps = 1e-6;
Physical Volume("block") = {1};
Physical Surface("top") = Surface In BoundingBox{-eps, -eps, -eps, L + eps, L + eps, eps};
Physical Surface("bottom") = Surface In BoundingBox{-eps, -eps, -L - eps, L + eps, L + eps, -L + eps};
Physical Surface("symmetry_x") = Surface In BoundingBox{-eps, -eps, -L - eps, eps, L + eps, eps};
Physical Surface("symmetry_y") = Surface In BoundingBox{-eps, -eps, -L - eps, L + eps, eps, eps};
