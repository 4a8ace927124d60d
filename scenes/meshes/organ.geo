// An organ-like body: an ellipsoid with semi-axes 35 x 25 x 15 mm about the
// origin, cut flat at z = -12 mm where it rests. Mesh it with, e.g.,
//   gmsh -3 organ.geo -clmin 0.004 -clmax 0.004 -format msh41 -o organ_4mm.msh
// (add -order 2 for tet10). Lengths in m.
SetFactory("OpenCASCADE");
Sphere(1) = {0, 0, 0, 1};
Dilate {{0, 0, 0}, {0.035, 0.025, 0.015}} { Volume{1}; }
Box(2) = {-1, -1, -1, 2, 2, 1 - 0.012};
BooleanDifference(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
Mesh.MeshSizeFromCurvature = 0;
Mesh.Algorithm3D = 1;
