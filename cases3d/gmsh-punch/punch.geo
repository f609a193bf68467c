// The demo's punch (cases3d/punch-anisotropic) rebuilt in Gmsh: the block [0, a] x [0, b] x [0, h] of
// n1 x n2 x nv hexahedra, extruded so that its nodes are those of frictopt's structured grid,
// the vertical layers graded as the grid's (layer k at height h (k/nv)^grading).
// Physical groups: "Body"; faces "Bottom" (x3 = 0, the contact surface and design patch),
// "Top", "Front" (x2 = 0), "Right" (x1 = a), "Back" (x2 = b), "Left" (x1 = 0).
DefineConstant[ a = 1.0, b = 1.0, h = 0.5, n1 = 16, n2 = 16, nv = 8, grading = 1.5 ];
For k In {1:nv}
  layer_count[k - 1] = 1;
  layer_height[k - 1] = (k / nv)^grading;
EndFor
Point(1) = {0, 0, 0};
line[] = Extrude {a, 0, 0} { Point{1}; Layers{n1}; };
surface[] = Extrude {0, b, 0} { Curve{line[1]}; Layers{n2}; Recombine; };
volume[] = Extrude {0, 0, h} { Surface{surface[1]}; Layers{layer_count[], layer_height[]}; Recombine; };
// Extruding a surface returns its top, the volume, then the lateral surfaces in the order of
// the base's boundary curves (x2 = 0, x1 = a, x2 = b, x1 = 0).
Physical Volume("Body") = {volume[1]};
Physical Surface("Bottom") = {surface[1]};
Physical Surface("Top") = {volume[0]};
Physical Surface("Front") = {volume[2]};
Physical Surface("Right") = {volume[3]};
Physical Surface("Back") = {volume[4]};
Physical Surface("Left") = {volume[5]};
