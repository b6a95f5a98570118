// The Hertz quarter sphere of examples/hertz/hemisphere.geo (R = 1, pole at
// the origin touching the plane z = 0, flat face at z = R), with the two
// element sizes of the threshold field as parameters so that race.py can
// make both race sizes from this one file:
//   gmsh -3 hemisphere.geo -setnumber hmin 0.0075 -setnumber hmax 0.19 -format msh22 -o small.msh
// hmin: size within r < 0.15 of the pole (the contact radius is ~0.11);
// hmax: size from r > 0.6 on. The defaults are examples/hertz's.
If (!Exists(hmin))
  hmin = 0.006;
EndIf
If (!Exists(hmax))
  hmax = 0.15;
EndIf
SetFactory("OpenCASCADE");
R = 1.0;
Sphere(1) = {0, 0, R, R};
Box(2) = {0, 0, 0, R, R, R};
BooleanIntersection(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
Field[1] = Distance;
Point(100) = {0, 0, 0};
Field[1].PointsList = {100};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = hmin;
Field[2].SizeMax = hmax;
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
