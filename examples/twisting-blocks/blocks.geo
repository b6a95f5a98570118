// Twisting blocks: a 1 x 1 x 0.5 block (upper) 0.001 above a 2 x 2 x 0.5
// block (lower), centred, each a square of nl x nl (nu x nu) quadrilaterals
// extruded into trilinear hexahedra (Hex8): non-matching meshes on the
// contact faces (lower cells 2/nl, upper 1/nu; the boxes share no node).
// The small initial gap: see README.md ("Why the blocks start apart").
//
//   gmsh -3 blocks.geo -format msh41 -o blocks.msh
//   gmsh -3 blocks.geo -setnumber nl 4 -setnumber nu 3 -format msh41 -o coarse.msh
DefineConstant[ nl = 8, nu = 5 ];
Point(1) = {-1, -1, 0};
Point(2) = {1, -1, 0};
Point(3) = {1, 1, 0};
Point(4) = {-1, 1, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1:4} = nl + 1;
Transfinite Surface{1};
Recombine Surface{1};
lower[] = Extrude {0, 0, 0.5} { Surface{1}; Layers{2}; Recombine; };

Point(1011) = {-0.5, -0.5, 0.501};
Point(1012) = {0.5, -0.5, 0.501};
Point(1013) = {0.5, 0.5, 0.501};
Point(1014) = {-0.5, 0.5, 0.501};
Line(1011) = {1011, 1012};
Line(1012) = {1012, 1013};
Line(1013) = {1013, 1014};
Line(1014) = {1014, 1011};
Curve Loop(1011) = {1011, 1012, 1013, 1014};
Plane Surface(1011) = {1011};
Transfinite Curve{1011:1014} = nu + 1;
Transfinite Surface{1011};
Recombine Surface{1011};
upper[] = Extrude {0, 0, 0.5} { Surface{1011}; Layers{Ceil(nu / 2)}; Recombine; };

Physical Volume("lower") = {lower[1]};
Physical Volume("upper") = {upper[1]};
Physical Surface("base") = {1};
Physical Surface("lower_top") = {lower[0]};
Physical Surface("upper_bottom") = {1011};
Physical Surface("upper_top") = {upper[0]};
