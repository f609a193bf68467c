// A 2D plate [0, 2] x [0, 1] of 4 x 2 quadrilaterals by extrusion; boundary lines "Bottom",
// "Top", "Left", "Right"; the body "Body".
Point(1) = {0, 0, 0};
line[] = Extrude {2, 0, 0} { Point{1}; Layers{4}; };
surface[] = Extrude {0, 1, 0} { Curve{line[1]}; Layers{2}; Recombine; };
Physical Surface("Body") = {surface[1]};
Physical Curve("Bottom") = {line[1]};
Physical Curve("Top") = {surface[0]};
Physical Curve("Right") = {surface[2]};
Physical Curve("Left") = {surface[3]};
