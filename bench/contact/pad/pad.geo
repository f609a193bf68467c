// A cylindrical pad with a boss (the slip-heavy benchmark of docs/scaling.md, "Many slipping
// contact nodes"): a disc of radius 50 mm and thickness 15 mm under a boss of radius 20 mm and
// height 20 mm. Its flat bottom is the contact surface and design patch; the boss's top face
// carries the press. Tetrahedra from Gmsh, subdivided into hexahedra by frictopt
// (docs/meshes.md). Physical groups: volume "Pad"; surfaces "Bottom" (z = 0), "BossTop"
// (z = 35 mm).
SetFactory("OpenCASCADE");
Cylinder(1) = {0, 0, 0, 0, 0, 0.015, 0.05};
Cylinder(2) = {0, 0, 0.015, 0, 0, 0.02, 0.02};
BooleanUnion(3) = {Volume{1}; Delete;}{Volume{2}; Delete;};
e = 1e-6;
bottom[] = Surface In BoundingBox{-1, -1, -e, 1, 1, e};
top[] = Surface In BoundingBox{-1, -1, 0.035 - e, 1, 1, 0.035 + e};
Physical Volume("Pad") = {3};
Physical Surface("Bottom") = {bottom[]};
Physical Surface("BossTop") = {top[]};
