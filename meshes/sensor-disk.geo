// The meridian section [0,R] x [-t,0] of a piezoelectric disk (x = r, y the axis) for a force
// sensor pressed by a ball: the top face split into the contact part [0,rc] x {0} and the
// rest, the mesh refined toward the origin; axis (x = 0), outer (x = R), bottom (y = -t). hc
// is the element size at the origin.
// Regenerate with: gmsh -2 sensor-disk.geo -o sensor-disk.msh
SetFactory("OpenCASCADE");
DefineConstant[ hc = 0.01, hf = 0.1, rc = 0.3, R = 2, t = 1 ];
Point(1) = {0, 0, 0}; Point(2) = {rc, 0, 0}; Point(3) = {R, 0, 0};
Point(4) = {R, -t, 0}; Point(5) = {0, -t, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5}; Line(5) = {5, 1};
Curve Loop(1) = {1, 2, 3, 4, 5};
Plane Surface(1) = {1};
Field[1] = Distance; Field[1].PointsList = {1};
Field[2] = Threshold; Field[2].InField = 1; Field[2].SizeMin = hc; Field[2].SizeMax = hf;
Field[2].DistMin = 0.2; Field[2].DistMax = 1;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0; Mesh.MeshSizeFromPoints = 0; Mesh.MeshSizeFromCurvature = 0;
Physical Curve("contact") = {1};
Physical Curve("top") = {2};
Physical Curve("outer") = {3};
Physical Curve("bottom") = {4};
Physical Curve("axis") = {5};
Physical Surface("body") = {1};
Mesh.MshFileVersion = 4.1;
