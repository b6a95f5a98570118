// A 4 x 1 x 1 bar, linear tetrahedra, written as MSH 4.1 and as an
// Abaqus deck by Gmsh, for tests/inp_reader.rs:
//   gmsh bar_tet.geo -3 -format msh41 -o bar_tet.msh
//   gmsh bar_tet.geo -3 -format inp -o bar_tet.inp
// (with Mesh.SaveGroupsOfNodes = 1 below, the .inp also has a *NSET per
// physical group)
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 4, 1, 1};
Mesh.CharacteristicLengthMax = 0.5;
Mesh.SaveGroupsOfNodes = 1;
// OpenCASCADE box faces: 1 x=0, 2 x=4, 3 y=0, 4 y=1, 5 z=0, 6 z=1
Physical Volume("bar") = {1};
Physical Surface("fixed") = {1};
Physical Surface("loaded") = {2};
Physical Surface("bottom") = {5};
// the corner (0, 0, 0) and the edge x = 0, y = 0 of the fixed end
Physical Point("origin") = {2};
Physical Curve("edge") = {1};
