// A 4 x 1 x 1 bar of 15-node wedges (faces Tri6 and Quad8): a triangle
// mesh of the end x = 0 extruded along x in 6 layers, second order
// without the face-centre nodes (Wedge15, not Wedge18), for
// tests/quadratic_elements.rs:
//   gmsh bar_wedge15.geo -3 -order 2 -format msh22 -o bar_wedge15.msh
Mesh.SecondOrderIncomplete = 1;
Point(1) = {0, 0, 0, 0.6};
Point(2) = {0, 1, 0, 0.6};
Point(3) = {0, 1, 1, 0.6};
Point(4) = {0, 0, 1, 0.6};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
out[] = Extrude {4, 0, 0} { Surface{1}; Layers{6}; Recombine; };
// out[0] the end x = 4, out[1] the volume, out[2..5] the sides
Physical Volume("bar") = {out[1]};
Physical Surface("fixed") = {1};
Physical Surface("loaded") = {out[0]};
