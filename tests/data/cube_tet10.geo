// A coarse second-order (Tet10) mesh of the unit cube, for the
// "unsupported element type" test.
// gmsh -3 cube_tet10.geo -format msh41 -o cube_tet10_41.msh
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Mesh.CharacteristicLengthMin = 1;
Mesh.CharacteristicLengthMax = 1;
Mesh.ElementOrder = 2;
Physical Volume("body") = {1};
