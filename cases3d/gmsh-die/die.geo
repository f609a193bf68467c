// A forming die (stamp) with fillets: a steel block 60 mm × 40 mm × 30 mm whose four vertical
// edges are rounded (radius 10 mm), so that its flat working face is a rounded rectangle — a
// non-rectangular contact patch — and whose bottom edges are filleted (radius 4 mm), the usual
// relief of a die's working face. OpenCASCADE kernel; Gmsh meshes it into tetrahedra, which
// frictopt subdivides into hexahedra (docs/meshes.md).
// Physical groups: "Body"; "Face" (the flat working face, z = 0: contact surface and design
// patch), "Top" (z = 30 mm, where the press holds the die), "Side" (everything else).
SetFactory("OpenCASCADE");
DefineConstant[ a = 0.060, b = 0.040, h = 0.030, r_corner = 0.010, r_edge = 0.004 ];
e = 1e-6;
Box(1) = {0, 0, 0, a, b, h};
vertical[] = Curve In BoundingBox{-e, -e, -e, e, e, h + e};
vertical[] += Curve In BoundingBox{a - e, -e, -e, a + e, e, h + e};
vertical[] += Curve In BoundingBox{a - e, b - e, -e, a + e, b + e, h + e};
vertical[] += Curve In BoundingBox{-e, b - e, -e, e, b + e, h + e};
rounded[] = Fillet{1}{vertical[]}{r_corner};
bottom_edges[] = Curve In BoundingBox{-e, -e, -e, a + e, b + e, e};
die[] = Fillet{rounded[0]}{bottom_edges[]}{r_edge};
face[] = Surface In BoundingBox{-e, -e, -e, a + e, b + e, e};
top[] = Surface In BoundingBox{-e, -e, h - e, a + e, b + e, h + e};
all[] = Surface{:};
side[] = all[];
side[] -= face[];
side[] -= top[];
Physical Volume("Body") = {die[0]};
Physical Surface("Face") = {face[]};
Physical Surface("Top") = {top[]};
Physical Surface("Side") = {side[]};
