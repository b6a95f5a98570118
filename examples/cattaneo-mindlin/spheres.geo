// Cattaneo–Mindlin: two identical elastic hemispheres (R = 1) pole to pole,
// pressed together and then sheared along x. Half models cut by the plane
// y = 0, which contains the load axis (x) and the axis of the press (z):
// a symmetry plane of both the press and the shear (u_y = 0 on it). The
// upper body has its pole at the origin and its flat face at z = R; the
// lower one is its mirror image, pole at z = -g0 (a gap g0 = 1e-5 keeps
// the two bodies' meshes apart) and flat face at z = -R - g0. Each body is
// cut by a plane into a cap (the curved surface within rc of the axis:
// the contact surfaces) and the rest. Linear tetrahedra refined under the
// contact (smin within dmin of the poles, growing to smax at dmax).
//
// The lower cap's curved surface is meshed as the mirror image
// z -> -z - g0 of the upper one (gmsh periodic surface with a
// reflection), so every secondary node sits on the axis line of a
// primary node, as in examples/two-spheres.
//
// gmsh -3 spheres.geo -format msh41 -o spheres.msh
// gmsh -3 spheres.geo -setnumber smin 0.012 -format msh41 -o coarse.msh   (the test's)
// The light press of the README ("A light press", light.toml): the contact's
// lengths x 1/5, the gap x 1/25:
// gmsh -3 spheres.geo -setnumber smin 0.0014 -setnumber dmin 0.026 -setnumber rc 0.032 -setnumber g0 4e-7 -format msh41 -o light.msh
// gmsh -3 spheres.geo -setnumber smin 0.0024 -setnumber dmin 0.026 -setnumber rc 0.032 -setnumber g0 4e-7 -format msh41 -o light-coarse.msh
SetFactory("OpenCASCADE");
DefineConstant[ rc = 0.16, smin = 0.008, dmin = 0.13, dmax = 0.6, smax = 0.2, g0 = 1e-5 ];
Geometry.AutoCoherence = 0;
R = 1.0;
eps = 1e-6;
zc = R - Sqrt(R * R - rc * rc);
Sphere(1) = {0, 0, R, R};
Box(2) = {-R, 0, 0, 2 * R, R, R};
BooleanIntersection(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
Rectangle(50) = {-R, 0, zc, 2 * R, R};
BooleanFragments{ Volume{3}; Delete; }{ Surface{50}; Delete; }
Sphere(4) = {0, 0, -R - g0, R};
Box(5) = {-R, 0, -R - g0, 2 * R, R, R};
BooleanIntersection(6) = { Volume{4}; Delete; }{ Volume{5}; Delete; };
Rectangle(51) = {-R, 0, -zc - g0, 2 * R, R};
BooleanFragments{ Volume{6}; Delete; }{ Surface{51}; Delete; }
// the pieces of the cutting rectangles outside the spheres
loose() = Surface{:};
loose() -= Abs(Boundary{ Volume{:}; });
Recursive Delete { Surface{loose()}; }
ucap() = Volume In BoundingBox{-R - eps, -eps, -eps, R + eps, R + eps, zc + eps};
uall() = Volume In BoundingBox{-R - eps, -eps, -eps, R + eps, R + eps, R + eps};
lcap() = Volume In BoundingBox{-R - eps, -eps, -zc - g0 - eps, R + eps, R + eps, -g0 + eps};
lall() = Volume In BoundingBox{-R - eps, -eps, -R - g0 - eps, R + eps, R + eps, -g0 + eps};
ucurved() = Abs(Boundary{ Volume{ucap()}; });
ucurved() -= Surface In BoundingBox{-R - eps, -eps, -eps, R + eps, eps, R + eps};
ucurved() -= Surface In BoundingBox{-R - eps, -eps, zc - eps, R + eps, R + eps, zc + eps};
lcurved() = Abs(Boundary{ Volume{lcap()}; });
lcurved() -= Surface In BoundingBox{-R - eps, -eps, -R - g0 - eps, R + eps, eps, -g0 + eps};
lcurved() -= Surface In BoundingBox{-R - eps, -eps, -zc - g0 - eps, R + eps, R + eps, -zc - g0 + eps};
// the lower cap = the upper cap mirrored in the plane z = -g0/2
Periodic Surface {lcurved(0)} = {ucurved(0)} Affine {1,0,0,0, 0,1,0,0, 0,0,-1,-g0, 0,0,0,1};
Field[1] = Distance;
Point(100) = {0, 0, 0};
Field[1].PointsList = {100};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = smin;
Field[2].SizeMax = smax;
Field[2].DistMin = dmin;
Field[2].DistMax = dmax;
Background Field = 2;
Mesh.CharacteristicLengthFromPoints = 0;
Mesh.CharacteristicLengthExtendFromBoundary = 0;
Physical Volume("upper") = {uall()};
Physical Volume("lower") = {lall()};
Physical Surface("top") = Surface In BoundingBox{-R - eps, -eps, R - eps, R + eps, R + eps, R + eps};
Physical Surface("bottom") = Surface In BoundingBox{-R - eps, -eps, -R - g0 - eps, R + eps, R + eps, -R - g0 + eps};
Physical Surface("symmetry_y") = Surface In BoundingBox{-R - eps, -eps, -R - g0 - eps, R + eps, eps, R + eps};
Physical Surface("upper_contact") = {ucurved()};
Physical Surface("lower_contact") = {lcurved()};
