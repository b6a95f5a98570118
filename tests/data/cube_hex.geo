// Unit cube, structured trilinear hexahedra (3 x 3 x 3).
// gmsh -3 cube_hex.geo -format msh41 -o cube_hex_41_ascii.msh   (and msh22, -bin)
// gmsh -3 cube_hex.geo -format inp -o cube_hex.inp   (tests/inp_reader.rs)
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Transfinite Curve{:} = 4;
Transfinite Surface{:};
Recombine Surface{:};
Transfinite Volume{1};
Physical Volume("body") = {1};
Physical Surface("bottom") = {5};
Physical Surface("top") = {6};
Physical Surface("contact") = {6};
