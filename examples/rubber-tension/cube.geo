// One eighth of a unit rubber cube (symmetry planes x = 0, y = 0, z = 0),
// a structured 4 × 4 × 4 hexahedral mesh.
// gmsh -3 cube.geo -format msh41 -o cube.msh
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Transfinite Curve{:} = 5;
Transfinite Surface{:};
Recombine Surface{:};
Transfinite Volume{1};
eps = 1e-6;
Physical Volume("rubber") = {1};
Physical Surface("xmin") = Surface In BoundingBox{-eps, -eps, -eps, eps, 1 + eps, 1 + eps};
Physical Surface("xmax") = Surface In BoundingBox{1 - eps, -eps, -eps, 1 + eps, 1 + eps, 1 + eps};
Physical Surface("ymin") = Surface In BoundingBox{-eps, -eps, -eps, 1 + eps, eps, 1 + eps};
Physical Surface("zmin") = Surface In BoundingBox{-eps, -eps, -eps, 1 + eps, 1 + eps, eps};
