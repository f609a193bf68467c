// cases3d/step-pad: the part as a CAD system hands it over — pad.step (made from pad-cad.geo by
// make_step.sh) read by Gmsh's OpenCASCADE kernel — with the physical groups frictopt needs:
// "Pad" (the body), "Face" (the cylindrical working face and its fillets: Γ_c and the design
// patch), "Top" (held by the press) and "Sides".
SetFactory("OpenCASCADE");
Merge "pad.step";
a = 0.04; b = 0.03; h = 0.02; R = 0.3; r_fillet = 0.003;
rim = R - Sqrt(R * R - a * a / 4);
eps = 1e-6;
// OpenCASCADE's bounding boxes of the fillets exceed the part by a fraction of a millimetre: the
// working face (the two halves of the cylinder and the four fillet patches) is what lies in a box
// 1 mm looser than the part, up to the fillets' top.
loose = 0.001;
face[] = Surface In BoundingBox{-loose, -loose, -loose, a + loose, b + loose, rim + r_fillet + loose};
top[] = Surface In BoundingBox{-eps, -eps, h - eps, a + eps, b + eps, h + eps};
all[] = Boundary{ Volume{1}; };
sides[] = all[];
sides[] -= face[];
sides[] -= top[];
// Tetrahedra of 0.8 mm in the band |x1 − a/2| < 5 mm of the working face where the contact strip
// lies (a cylinder this flat touches along a strip a few millimetres wide), growing to the case's
// size elsewhere: the contact nodes off the strip stay few, which keeps the dense contact algebra small.
Field[1] = Box;
Field[1].VIn = 0.0008;
Field[1].VOut = 0.004;
Field[1].XMin = a / 2 - 0.005;
Field[1].XMax = a / 2 + 0.005;
Field[1].YMin = -1;
Field[1].YMax = 1;
Field[1].ZMin = -1;
Field[1].ZMax = 0.003;
Field[1].Thickness = 0.004;
Background Field = 1;
Physical Volume("Pad") = {1};
Physical Surface("Face") = {face[]};
Physical Surface("Top") = {top[]};
Physical Surface("Sides") = {sides[]};
