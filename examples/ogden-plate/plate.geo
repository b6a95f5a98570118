// Quarter of a rubber plate (full plate 10 × 4 × 1) lying on a rigid
// foundation z = 0: x ∈ [0, L/2], y ∈ [0, W/2], z ∈ [0, T], with the
// symmetry planes x = 0 and y = 0 through the plate's centre. The top face
// is split at x = L/2 − A so that the strip x ∈ [L/2 − A, L/2] (the full
// plate's edge strip of width A) carries the pressure.
//
// Hexahedra: the bottom face is meshed with transfinite quadrangles and
// extruded through the thickness. N elements per unit length in x and y,
// NZ through the thickness:
//   gmsh -3 plate.geo -format msh2 -o plate.msh                    (N = 6, NZ = 4)
//   gmsh -3 plate.geo -setnumber N 3 -setnumber NZ 2 -format msh2 -o plate-coarse.msh

DefineConstant[ N = {6, Name "elements per unit length (x, y)"} ];
DefineConstant[ NZ = {4, Name "elements through the thickness"} ];

L = 10;   // plate length (x)
W = 4;    // plate width (y)
T = 1;    // thickness (z)
A = 1.5;  // width of each loaded edge strip

X1 = L/2 - A;
Point(1) = {0, 0, 0};
Point(2) = {X1, 0, 0};
Point(3) = {L/2, 0, 0};
Point(4) = {L/2, W/2, 0};
Point(5) = {X1, W/2, 0};
Point(6) = {0, W/2, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 6};
Line(6) = {6, 1};
Line(7) = {2, 5};
Curve Loop(1) = {1, 7, 5, 6};
Curve Loop(2) = {2, 3, 4, -7};
Plane Surface(1) = {1};
Plane Surface(2) = {2};

Transfinite Curve{1, 5} = Round(X1 * N) + 1;
Transfinite Curve{2, 4} = Round(A * N) + 1;
Transfinite Curve{3, 6, 7} = Round(W / 2 * N) + 1;
Transfinite Surface{1, 2};
Recombine Surface{1, 2};

free[] = Extrude {0, 0, T} { Surface{1}; Layers{NZ}; Recombine; };
strip[] = Extrude {0, 0, T} { Surface{2}; Layers{NZ}; Recombine; };
// free[0], strip[0]: top faces; free[1]: the volume; then the sides in the
// order of the curve loops: free[2] on y = 0, free[5] on x = 0;
// strip[2] on y = 0, strip[3] on x = L/2 (the free edge face)

Physical Volume("plate") = {free[1], strip[1]};
Physical Surface("bottom") = {1, 2};
Physical Surface("load") = {strip[0]};
Physical Surface("symmetry_x") = {free[5]};
Physical Surface("symmetry_y") = {free[2], strip[2]};
