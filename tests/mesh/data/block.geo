// A structured block [0, a] x [0, b] x [0, h] of n1 x n2 x nv hexahedra, built by extrusion so
// that its nodes are those of frictopt's structured grid (tests/mesh/gmsh_mesh_test.cpp).
// Physical groups: the body "Body"; faces "Bottom" (x3 = 0), "Top", "Left" (x1 = 0), "Right",
// "Front" (x2 = 0), "Back".
DefineConstant[ a = 1.0, b = 1.0, h = 0.5, n1 = 2, n2 = 2, nv = 1 ];
Point(1) = {0, 0, 0};
line[] = Extrude {a, 0, 0} { Point{1}; Layers{n1}; };
surface[] = Extrude {0, b, 0} { Curve{line[1]}; Layers{n2}; Recombine; };
volume[] = Extrude {0, 0, h} { Surface{surface[1]}; Layers{nv}; Recombine; };
// Extrude of a surface returns: top, volume, then the lateral surfaces in the order of the
// boundary curves of the base (front: x2 = 0, right, back, left).
Physical Volume("Body") = {volume[1]};
Physical Surface("Bottom") = {surface[1]};
Physical Surface("Top") = {volume[0]};
Physical Surface("Front") = {volume[2]};
Physical Surface("Right") = {volume[3]};
Physical Surface("Back") = {volume[4]};
Physical Surface("Left") = {volume[5]};
