// An unstructured body: a cylinder of radius 0.5 and height 0.4 (OpenCASCADE), meshed into
// tetrahedra by Gmsh, which frictopt subdivides into hexahedra. Faces "Bottom", "Top", "Side".
SetFactory("OpenCASCADE");
Cylinder(1) = {0, 0, 0, 0, 0, 0.4, 0.5};
Physical Volume("Body") = {1};
Physical Surface("Side") = {1};
Physical Surface("Top") = {2};
Physical Surface("Bottom") = {3};
