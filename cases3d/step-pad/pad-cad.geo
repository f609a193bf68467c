// The CAD part of cases3d/step-pad, in Gmsh's OpenCASCADE kernel: a steel pad 40 mm × 30 mm ×
// 20 mm whose working face is a cylinder of radius 300 mm about an axis along x2 (the lowest line
// at x1 = 20 mm, x3 = 0), its two ends (the arcs at x2 = 0 and x2 = 30 mm) rounded with r = 3 mm.
// make_step.sh exports it to pad.step (the file the case's pad.geo reads), as a CAD system would
// hand over a part. (Rounding all four edges of the face made Gmsh 4.11 fail to mesh the corner
// patches where the fillets meet: "Impossible to mesh periodic surface".)
SetFactory("OpenCASCADE");
a = 0.04; b = 0.03; h = 0.02; R = 0.3; r_fillet = 0.003;
Box(1) = {0, 0, 0, a, b, h};
Cylinder(2) = {a / 2, -0.01, R, 0, b + 0.02, 0, R};
BooleanIntersection(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
// The working face's end arcs lie in the planes x2 = 0 and x2 = b, below the height of its
// straight edges, R − sqrt(R² − (a/2)²).
rim = R - Sqrt(R * R - a * a / 4);
eps = 1e-6;
edges[] = Curve In BoundingBox{-eps, -eps, -eps, a + eps, eps, rim + eps};
edges[] += Curve In BoundingBox{-eps, b - eps, -eps, a + eps, b + eps, rim + eps};
Fillet{3}{edges[]}{r_fillet}
