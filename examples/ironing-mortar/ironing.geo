// Ironing after Puso & Laursen (2004), 3D: a stiff die, a cylindrical
// segment of radius R, pressed into a soft slab L × W × H and slid along x.
//   gmsh -3 ironing.geo -format msh41 -o ironing.msh
// and the test's coarser mesh (tests/ironing_mortar.rs):
//   gmsh -3 ironing.geo -setnumber NX 12 -setnumber NY 4 -setnumber NZ 4 \
//     -setnumber NA 16 -setnumber NYD 5 -format msh41 -o coarse.msh
//
// Slab: x ∈ [0, L], y ∈ [0, W], z ∈ [0, H]; NX × NY × NZ hexahedra.
// Die: the annular sector between radii R − D (the loaded face `die_top`)
// and R (the contact face `die_arc`), ±A about the downward vertical, its
// axis along y at (XC, H + G + R): the arc clears the slab's top by G along
// the line x = XC (the dual-weighted gap of a slab node right under a
// curved arc that touches it is negative, −5e-3 here, which the case
// refuses as an initial overlap; the case presses G + 1.4). It spans
// y ∈ [−M, W + M], wider than the slab, so that the slab's top (the
// secondary surface) stays covered across its width.

L = 9;  W = 4;  H = 3;
If (!Exists(NX)) NX = 18; EndIf
If (!Exists(NY)) NY = 8; EndIf
If (!Exists(NZ)) NZ = 6; EndIf
If (!Exists(NA)) NA = 24; EndIf
If (!Exists(NYD)) NYD = 9; EndIf
R = 3;  D = 1;  A = 70 * Pi / 180;  XC = 2.5;  M = 0.5;  G = 0.01;
NR = 2;

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

ZC = H + G + R;
Point(10) = {XC, -M, ZC};
Point(11) = {XC - R * Sin(A), -M, ZC - R * Cos(A)};
Point(12) = {XC + R * Sin(A), -M, ZC - R * Cos(A)};
Point(13) = {XC + (R - D) * Sin(A), -M, ZC - (R - D) * Cos(A)};
Point(14) = {XC - (R - D) * Sin(A), -M, ZC - (R - D) * Cos(A)};
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

slab[] = Extrude {0, W, 0} { Surface{1}; Layers{NY}; Recombine; };
die[] = Extrude {0, W + 2 * M, 0} { Surface{2}; Layers{NYD}; Recombine; };
// [0] the far face, [1] the volume, then the sides in the order of the
// curve loop: slab[2] bottom, slab[4] top; die[2] the contact arc, die[4]
// the loaded inner arc

Physical Volume("slab") = {slab[1]};
Physical Volume("die") = {die[1]};
Physical Surface("slab_bottom") = {slab[2]};
Physical Surface("slab_top") = {slab[4]};
Physical Surface("die_arc") = {die[2]};
Physical Surface("die_top") = {die[4]};
