// Quarter of a thick-walled cylinder, inner radius 1, outer radius 2,
// height 0.5, meshed with linear tetrahedra.
// gmsh -3 cylinder.geo -format msh41 -o cylinder.msh
SetFactory("OpenCASCADE");
a = 1.0; b = 2.0; h = 0.5;
Cylinder(1) = {0, 0, 0, 0, 0, h, b, Pi/2};
Cylinder(2) = {0, 0, 0, 0, 0, h, a, Pi/2};
BooleanDifference(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
Mesh.CharacteristicLengthMax = 0.12;
eps = 1e-6;
Physical Volume("body") = {3};
// only the curved inner face lies entirely inside this box (the planar
// faces reach out to r = b)
Physical Surface("inner") = Surface In BoundingBox{-eps, -eps, -eps, a + eps, a + eps, h + eps};
Physical Surface("symmetry_x") = Surface In BoundingBox{-eps, -eps, -eps, eps, b + eps, h + eps};
Physical Surface("symmetry_y") = Surface In BoundingBox{-eps, -eps, -eps, b + eps, eps, h + eps};
Physical Surface("bottom") = Surface In BoundingBox{-eps, -eps, -eps, b + eps, b + eps, eps};
Physical Surface("top") = Surface In BoundingBox{-eps, -eps, h - eps, b + eps, b + eps, h + eps};
