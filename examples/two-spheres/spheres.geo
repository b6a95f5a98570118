// Two identical elastic hemispheres (R = 1) pole to pole: quarter models
// (symmetry planes x = 0 and y = 0). The upper one has its pole at the
// origin and its flat face at z = R; the lower one is its mirror image,
// pole at z = -g0 (a gap g0 = 1e-5 keeps the two bodies' meshes apart) and
// flat face at z = -R - g0. Linear tetrahedra refined under the contact
// (SizeMin within 0.15 of the poles, growing to SizeMax).
// gmsh -3 spheres.geo -format msh41 -o spheres.msh
SetFactory("OpenCASCADE");
Geometry.AutoCoherence = 0;
R = 1.0;
g0 = 1e-5;
Sphere(1) = {0, 0, R, R};
Box(2) = {0, 0, 0, R, R, R};
BooleanIntersection(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
Sphere(4) = {0, 0, -R - g0, R};
Box(5) = {0, 0, -R - g0, R, R, R};
BooleanIntersection(6) = { Volume{4}; Delete; }{ Volume{5}; Delete; };
Field[1] = Distance;
Point(100) = {0, 0, 0};
Field[1].PointsList = {100};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = 0.008;
Field[2].SizeMax = 0.15;
Field[2].DistMin = 0.15;
Field[2].DistMax = 0.6;
Background Field = 2;
Mesh.CharacteristicLengthFromPoints = 0;
Mesh.CharacteristicLengthExtendFromBoundary = 0;
eps = 1e-6;
Physical Volume("upper") = {3};
Physical Volume("lower") = {6};
top() = Surface In BoundingBox{-eps, -eps, R - eps, R + eps, R + eps, R + eps};
bottom() = Surface In BoundingBox{-eps, -eps, -R - g0 - eps, R + eps, R + eps, -R - g0 + eps};
usx() = Surface In BoundingBox{-eps, -eps, -eps, eps, R + eps, R + eps};
usy() = Surface In BoundingBox{-eps, -eps, -eps, R + eps, eps, R + eps};
lsx() = Surface In BoundingBox{-eps, -eps, -R - g0 - eps, eps, R + eps, -g0 + eps};
lsy() = Surface In BoundingBox{-eps, -eps, -R - g0 - eps, R + eps, eps, -g0 + eps};
ucurved() = Abs(Boundary{ Volume{3}; });
ucurved() -= {top(), usx(), usy()};
lcurved() = Abs(Boundary{ Volume{6}; });
lcurved() -= {bottom(), lsx(), lsy()};
Physical Surface("top") = {top()};
Physical Surface("bottom") = {bottom()};
Physical Surface("symmetry_x") = {usx(), lsx()};
Physical Surface("symmetry_y") = {usy(), lsy()};
Physical Surface("upper_contact") = {ucurved()};
Physical Surface("lower_contact") = {lcurved()};
