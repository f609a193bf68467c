// The Hertz cap of hertz_cap.geo with the sizes for P1 tetrahedra kept as they are
// ([mesh] element = "tet4"): a third of the subdivided mesh's tetrahedron sizes, which gives
// about the unknowns of the subdivided hexahedra (tests/study/gmsh_hertz_cap_slow_test.cpp).
s_apex = 0.04 / 3;
s_far = 0.12 / 3;
Include "hertz_cap.geo";
