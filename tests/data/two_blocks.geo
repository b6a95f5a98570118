// Two stacked unit cubes sharing the face z = 1, in two physical volumes:
// "lower" (named) and 7 (no name, so the reader calls the region "7").
// gmsh -3 two_blocks.geo -format msh41 -save_parametric -o two_blocks_41_param.msh
// gmsh -3 two_blocks.geo -format msh22 -bin -o two_blocks_22_bin.msh
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Box(2) = {0, 0, 1, 1, 1, 1};
BooleanFragments{ Volume{1}; Delete; }{ Volume{2}; Delete; }
Mesh.CharacteristicLengthMax = 0.5;
Physical Volume("lower") = {1};
Physical Volume(7) = {2};
Physical Surface("bottom") = {Surface In BoundingBox{-0.1, -0.1, -0.1, 1.1, 1.1, 0.1}};
Physical Surface("interface") = {Surface In BoundingBox{-0.1, -0.1, 0.9, 1.1, 1.1, 1.1}};
