// Unit cube, linear tetrahedra.
// gmsh -3 cube_tet.geo -format msh41 -o cube_tet_41_ascii.msh   (and msh22, -bin)
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Mesh.CharacteristicLengthMax = 0.4;
// OpenCASCADE box faces: 1 x=0, 2 x=1, 3 y=0, 4 y=1, 5 z=0, 6 z=1
Physical Volume("body") = {1};
Physical Surface("bottom") = {5};
Physical Surface("top") = {6};
// the same surface in a second group: its facets belong to both sets
Physical Surface("contact") = {6};
