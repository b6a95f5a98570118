// The paper's example 1 (Cavalieri et al., §7.1, after Armero & Petocz
// 1999): an elastic block [0, 4] × [0, 0.5] × [0, 1] on a rigid foundation
// z = 0, in a 3D plane-strain set-up (y is the out-of-plane direction; the
// y displacement is held on the faces y = 0 and y = 0.5). Unstructured
// linear tetrahedra of size 0.12: about 1.6 k nodes and 7 k tetrahedra, as
// in the paper (1583 nodes, 7241 tetrahedra).
// gmsh -3 block.geo -format msh41 -o block.msh
SetFactory("OpenCASCADE");
L = 4.0;  // length (x)
T = 0.5;  // thickness (y, plane strain)
H = 1.0;  // height (z)
Box(1) = {0, 0, 0, L, T, H};
Mesh.CharacteristicLengthMin = 0.12;
Mesh.CharacteristicLengthMax = 0.12;
Mesh.Algorithm3D = 1;
Mesh.RandomFactor = 1e-9;
eps = 1e-6;
Physical Volume("block") = {1};
Physical Surface("bottom") = Surface In BoundingBox{-eps, -eps, -eps, L + eps, T + eps, eps};
Physical Surface("top") = Surface In BoundingBox{-eps, -eps, H - eps, L + eps, T + eps, H + eps};
Physical Surface("left") = Surface In BoundingBox{-eps, -eps, -eps, eps, T + eps, H + eps};
Physical Surface("right") = Surface In BoundingBox{L - eps, -eps, -eps, L + eps, T + eps, H + eps};
Physical Surface("front") = Surface In BoundingBox{-eps, -eps, -eps, L + eps, eps, H + eps};
Physical Surface("back") = Surface In BoundingBox{-eps, T - eps, -eps, L + eps, T + eps, H + eps};
