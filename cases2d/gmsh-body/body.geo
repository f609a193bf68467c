// A 2D body imported from Gmsh: the thesis' 2 m × 1 m body with rounded corners (radius 0.3 m),
// so that its flat bottom — the contact surface and design patch — spans x1 in [0.3, 1.7] and
// the rounded corners are free boundary. Quadrilaterals by Gmsh's recombination (Blossom) of its
// frontal-Delaunay triangles,
// frictopt's Q1 cells (docs/meshes.md). Physical groups: "Body"; lines "Bottom" (x2 = 0),
// "Top" (x2 = 1), "Left" (x1 = 0), "Right" (x1 = 2), "Corners" (the four arcs).
SetFactory("OpenCASCADE");
Rectangle(1) = {0, 0, 0, 2.0, 1.0, 0.3};
Mesh.RecombineAll = 1;
e = 1e-6;
bottom[] = Curve In BoundingBox{-e, -e, -e, 2 + e, e, e};
top[] = Curve In BoundingBox{-e, 1 - e, -e, 2 + e, 1 + e, e};
left[] = Curve In BoundingBox{-e, -e, -e, e, 1 + e, e};
right[] = Curve In BoundingBox{2 - e, -e, -e, 2 + e, 1 + e, e};
corners[] = Curve{:};
corners[] -= bottom[];
corners[] -= top[];
corners[] -= left[];
corners[] -= right[];
Physical Surface("Body") = {1};
Physical Curve("Bottom") = {bottom[]};
Physical Curve("Top") = {top[]};
Physical Curve("Left") = {left[]};
Physical Curve("Right") = {right[]};
Physical Curve("Corners") = {corners[]};
