// An unstructured 2D plate [0, 1] x [0, 0.6] with a circular hole of radius 0.15 at
// (0.6, 0.3) (OpenCASCADE): Gmsh meshes it into triangles, which frictopt subdivides into
// quadrilaterals (docs/meshes.md). For the manufactured-solution convergence test
// (tests/mesh/imported_convergence_test.cpp): every boundary carries the exact solution, so the
// groups only need to cover the boundary. Curves "Outer" (the rectangle) and "Hole".
SetFactory("OpenCASCADE");
Rectangle(1) = {0, 0, 0, 1, 0.6};
Disk(2) = {0.6, 0.3, 0, 0.15, 0.15};
BooleanDifference(3) = { Surface{1}; Delete; }{ Surface{2}; Delete; };
Physical Surface("Body") = {3};
Physical Curve("Outer") = {1, 2, 3, 4};
Physical Curve("Hole") = {5};
