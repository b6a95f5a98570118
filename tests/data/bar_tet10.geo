// A 4 x 1 x 1 bar, quadratic tetrahedra (Tet10, faces Tri6), written as
// MSH 4.1 and as an Abaqus deck (C3D10) by Gmsh, for
// tests/quadratic_elements.rs:
//   gmsh bar_tet10.geo -3 -order 2 -format msh41 -o bar_tet10.msh
//   gmsh bar_tet10.geo -3 -order 2 -format inp -o bar_tet10.inp
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 4, 1, 1};
Mesh.CharacteristicLengthMax = 0.7;
Mesh.SaveGroupsOfNodes = 1;
// OpenCASCADE box faces: 1 x=0, 2 x=4, 3 y=0, 4 y=1, 5 z=0, 6 z=1
Physical Volume("bar") = {1};
Physical Surface("fixed") = {1};
Physical Surface("loaded") = {2};
Physical Surface("bottom") = {5};
