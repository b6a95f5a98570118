// Ironing, after Puso & Laursen (2004): a stiff die, a cylindrical segment,
// pressed into a soft slab and slid along it. A plane-strain slice: the
// x–z cross-section is meshed with transfinite quadrangles and extruded by
// one layer of hexahedra through the thickness T (y); the case holds u_y = 0
// on both faces y = 0 and y = T.
//   gmsh -3 ironing.geo -format msh41 -o ironing.msh
//
// Slab: x ∈ [0, L], z ∈ [0, H], NX × NZ elements.
// Die: the annular sector between radii R − D (the loaded face) and R
// (the contact arc), ±A degrees about the downward vertical, its axis at
// (XC, H + R): the arc touches the slab's top at x = XC, the die lies above
// it (inside the circle of radius R).

L = 9;  H = 1;  T = 0.125;
NX = 72;  NZ = 8;
R = 1;  D = 0.5;  A = 60 * Pi / 180;  XC = 2;
NA = 36;  NR = 4;

// slab
Point(1) = {0, 0, 0};
Point(2) = {L, 0, 0};
Point(3) = {L, 0, H};
Point(4) = {0, 0, H};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = NX + 1;
Transfinite Curve{2, 4} = NZ + 1;
Transfinite Surface{1};
Recombine Surface{1};

// die
ZC = H + R;
Point(10) = {XC, 0, ZC};
Point(11) = {XC - R * Sin(A), 0, ZC - R * Cos(A)};
Point(12) = {XC + R * Sin(A), 0, ZC - R * Cos(A)};
Point(13) = {XC + (R - D) * Sin(A), 0, ZC - (R - D) * Cos(A)};
Point(14) = {XC - (R - D) * Sin(A), 0, ZC - (R - D) * Cos(A)};
Circle(11) = {11, 10, 12};
Line(12) = {12, 13};
Circle(13) = {13, 10, 14};
Line(14) = {14, 11};
Curve Loop(2) = {11, 12, 13, 14};
Plane Surface(2) = {2};
Transfinite Curve{11, 13} = NA + 1;
Transfinite Curve{12, 14} = NR + 1;
Transfinite Surface{2};
Recombine Surface{2};

slab[] = Extrude {0, T, 0} { Surface{1}; Layers{1}; Recombine; };
die[] = Extrude {0, T, 0} { Surface{2}; Layers{1}; Recombine; };
// [0] the face y = T, [1] the volume, then the sides in the order of the
// curve loop: slab[2] bottom, slab[4] top; die[2] the contact arc, die[4]
// the loaded outer arc

Physical Volume("slab") = {slab[1]};
Physical Volume("die") = {die[1]};
Physical Surface("slab_bottom") = {slab[2]};
Physical Surface("slab_top") = {slab[4]};
Physical Surface("die_arc") = {die[2]};
Physical Surface("die_top") = {die[4]};
Physical Surface("front") = {1, 2};
Physical Surface("back") = {slab[0], die[0]};
