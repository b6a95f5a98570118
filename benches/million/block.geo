// The million-dof benchmark's body (benches/million/README.md): half of an
// elastic block [-1, 1] x [0, 1] x [-1, 0] (top face z = 0, symmetry plane
// y = 0) under a rigid sphere touching it at the origin, meshed with
// structured 8-node hexahedra (Extrude with Layers and Recombine), graded
// toward the contact: along each axis the node at the uniform position
// xi in [-1, 1] (in [0, 1] for y, [-1, 0] for z) is placed at
//     x(xi) = xi (alpha + (1 - alpha) xi^2),
// so the spacing is alpha (default 0.3) of the uniform one at the origin
// and 3 - 2 alpha of it at the far faces. `n` sets the size: 2n elements
// along x, n along y and round(0.8n) along z; (2n + 1)(n + 1)(0.8n + 1) nodes,
// 3 dofs each:
//     n = 30: 141 825 dofs   n = 45: 464 646 dofs   n = 60: 1 085 007 dofs
// gmsh -3 block.geo -setnumber n 60 -format msh41 -bin -o block.msh
DefineConstant[ n = 30, alpha = 0.3 ];
nx = 2 * n;
ny = n;
nz = Round(0.8 * n);

// x(xi) for xi in [0, 1] (odd in xi)
Macro Graded
  g = xi * (alpha + (1 - alpha) * xi * xi);
Return

// x: from -1 to 1, fine in the middle (cumulative fractions of the length 2)
For i In {1 : nx}
  xi = -1 + 2 * i / nx;
  s = 1;
  If (xi < 0)
    xi = -xi;
    s = -1;
  EndIf
  Call Graded;
  layer_x[i - 1] = 1;
  height_x[i - 1] = (1 + s * g) / 2;
EndFor
// y: from 0 to 1, fine at y = 0
For i In {1 : ny}
  xi = i / ny;
  Call Graded;
  layer_y[i - 1] = 1;
  height_y[i - 1] = g;
EndFor
// z: from 0 down to -1, fine at z = 0
For i In {1 : nz}
  xi = i / nz;
  Call Graded;
  layer_z[i - 1] = 1;
  height_z[i - 1] = g;
EndFor

Point(1) = {-1, 0, 0};
line[] = Extrude {2, 0, 0} { Point{1}; Layers{ layer_x[], height_x[] }; };
face[] = Extrude {0, 1, 0} { Line{line[1]}; Layers{ layer_y[], height_y[] }; Recombine; };
body[] = Extrude {0, 0, -1} { Surface{face[1]}; Layers{ layer_z[], height_z[] }; Recombine; };

eps = 1e-6;
Physical Volume("block") = {body[1]};
Physical Surface("top") = Surface In BoundingBox{-1 - eps, -eps, -eps, 1 + eps, 1 + eps, eps};
Physical Surface("bottom") = Surface In BoundingBox{-1 - eps, -eps, -1 - eps, 1 + eps, 1 + eps, -1 + eps};
Physical Surface("symmetry_y") = Surface In BoundingBox{-1 - eps, -eps, -1 - eps, 1 + eps, eps, eps};
