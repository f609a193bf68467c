// Hertz contact on an imported body (docs/meshes.md): a cylinder of radius 0.5 m and height
// 0.5 m above a spherical cap of curvature radius R = 2 m (OpenCASCADE), apex at the origin,
// pressed on the rigid plane x3 = 0 by moving its top down (tests/study/gmsh_hertz_cap_slow_test.cpp).
// Gmsh meshes it into tetrahedra of size s_apex within 0.2 m of the apex, growing to s_far
// at 0.45 m; frictopt subdivides them into hexahedra (cells about half the tetrahedron size),
// or keeps them as P1 cells (hertz_cap_p1.geo sets finer sizes and includes this file).
// No node is forced at the apex: an embedded point there made Gmsh 4.8's surface mesher of the
// sphere loop, so the peak pressure is read from the profile fit. Groups: "Body", "Cap" (Γ_c),
// "Top", "Side".
SetFactory("OpenCASCADE");
DefineConstant[ R = 2.0, Rc = 0.5, H = 0.5, s_apex = 0.04, s_far = 0.12 ];
cap_height = R - Sqrt(R * R - Rc * Rc);
Sphere(1) = {0, 0, R, R};
// The sphere's parametric poles lie on its axis; turned about x1 they leave the apex, where a
// pole would be a singular point of the surface mesh.
Rotate {{1, 0, 0}, {0, 0, R}, Pi / 2} { Volume{1}; }
Cylinder(2) = {0, 0, 0, 0, 0, cap_height, Rc};
BooleanIntersection(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
Cylinder(4) = {0, 0, cap_height, 0, 0, H, Rc};
BooleanUnion(5) = { Volume{3}; Delete; }{ Volume{4}; Delete; };
eps = 1e-6;
// Loose boxes: OpenCASCADE's bounding box of a trimmed sphere exceeds the surface.
cap[] = Surface In BoundingBox{-Rc - 0.05, -Rc - 0.05, -0.05, Rc + 0.05, Rc + 0.05, cap_height + H / 2};
top[] = Surface In BoundingBox{-Rc - eps, -Rc - eps, cap_height + H - eps, Rc + eps, Rc + eps, cap_height + H + eps};
all[] = Boundary{ Volume{5}; };
side[] = all[];
side[] -= cap[];
side[] -= top[];
apex = newp;
Point(apex) = {0, 0, 0};
Field[1] = Distance;
Field[1].PointsList = {apex};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = s_apex;
Field[2].SizeMax = s_far;
Field[2].DistMin = 0.2;
Field[2].DistMax = 0.45;
Background Field = 2;
Physical Volume("Body") = {5};
Physical Surface("Cap") = {cap[]};
Physical Surface("Top") = {top[]};
Physical Surface("Side") = {side[]};
