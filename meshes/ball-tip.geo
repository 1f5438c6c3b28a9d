// A rigid ball of radius 1 centred at (0, 0, 1) as a closed triangulated surface (an STL
// file), its triangles small near its lowest point, the origin, where it touches a face z = 0:
// the shape of a tip for `[foundation] kind = "surface"`, and the test of the surface gaps
// against the analytic sphere.
// Regenerate with: gmsh -2 ball-tip.geo -o ball-tip.stl
SetFactory("OpenCASCADE");
Sphere(1) = {0, 0, 1, 1};
Point(100) = {0, 0, 0};
Field[1] = Distance; Field[1].PointsList = {100};
Field[2] = Threshold; Field[2].InField = 1; Field[2].SizeMin = 0.004; Field[2].SizeMax = 0.2;
Field[2].DistMin = 0.03; Field[2].DistMax = 0.8;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0; Mesh.MeshSizeFromPoints = 0; Mesh.MeshSizeFromCurvature = 0;
Mesh.Binary = 1;
