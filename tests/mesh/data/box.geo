// An unstructured box [0, 1] x [0, 1] x [0, 0.4] (OpenCASCADE): Gmsh meshes it into
// tetrahedra, which frictopt subdivides into distorted hexahedra; its faces are planar, so
// linear fields are exact solutions for the patch test. Faces "Left" (x1 = 0), "Right",
// "Front" (x2 = 0), "Back", "Bottom" (x3 = 0), "Top".
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 0.4};
Physical Volume("Body") = {1};
Physical Surface("Left") = {1};
Physical Surface("Right") = {2};
Physical Surface("Front") = {3};
Physical Surface("Back") = {4};
Physical Surface("Bottom") = {5};
Physical Surface("Top") = {6};
