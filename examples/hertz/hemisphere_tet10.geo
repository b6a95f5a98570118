// The hemisphere of hemisphere.geo (a quarter of an elastic hemisphere of
// radius R = 1, its pole at the origin touching the plane z = 0, its flat
// face at z = R) meshed with quadratic tetrahedra (Tet10): element size
// 0.012 within r < 0.15 of the pole, growing to 0.15; the surfaces'
// names as there.
// gmsh -3 -order 2 hemisphere_tet10.geo -format msh41 -o hemisphere_tet10.msh
SetFactory("OpenCASCADE");
R = 1.0;
hmin = 0.012;
Sphere(1) = {0, 0, R, R};
Box(2) = {0, 0, 0, R, R, R};
BooleanIntersection(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
Field[1] = Distance;
Point(100) = {0, 0, 0};
Field[1].PointsList = {100};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = hmin;
Field[2].SizeMax = 0.15;
Field[2].DistMin = 0.15;
Field[2].DistMax = 0.6;
Background Field = 2;
Mesh.CharacteristicLengthFromPoints = 0;
Mesh.CharacteristicLengthExtendFromBoundary = 0;
eps = 1e-6;
Physical Volume("ball") = {3};
top() = Surface In BoundingBox{-eps, -eps, R - eps, R + eps, R + eps, R + eps};
sx() = Surface In BoundingBox{-eps, -eps, -eps, eps, R + eps, R + eps};
sy() = Surface In BoundingBox{-eps, -eps, -eps, R + eps, eps, R + eps};
curved() = Abs(Boundary{ Volume{3}; });
curved() -= {top(), sx(), sy()};
Physical Surface("top") = {top()};
Physical Surface("symmetry_x") = {sx()};
Physical Surface("symmetry_y") = {sy()};
Physical Surface("contact") = {curved()};
