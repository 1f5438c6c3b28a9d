// The meridian section [0,L] x [-L,0] of a cylinder (x = r, y the axis) for axisymmetric
// indentation: the top face split into the contact part [0,rc] x {0} and the rest, the mesh
// refined toward the origin; axis (x = 0), outer (x = L), bottom (y = -L). hc is the element
// size at the origin; L = 20 makes it nearly a half-space for a contact radius of 0.1.
// Regenerate with: gmsh -2 -setnumber hc H indent-axisym.geo -o indent-axisym-hH.msh (H = 0.02,
// 0.01)
SetFactory("OpenCASCADE");
DefineConstant[ hc = 0.01, rc = 0.3, L = 20 ];
hf = 50 * hc; // the far field refined with the centre, so that the whole body's compliance converges
Point(1) = {0, 0, 0}; Point(2) = {rc, 0, 0}; Point(3) = {L, 0, 0};
Point(4) = {L, -L, 0}; Point(5) = {0, -L, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5}; Line(5) = {5, 1};
Curve Loop(1) = {1, 2, 3, 4, 5};
Plane Surface(1) = {1};
Field[1] = Distance; Field[1].PointsList = {1};
Field[2] = Threshold; Field[2].InField = 1; Field[2].SizeMin = hc; Field[2].SizeMax = hf;
Field[2].DistMin = 0.15; Field[2].DistMax = 15;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0; Mesh.MeshSizeFromPoints = 0; Mesh.MeshSizeFromCurvature = 0;
Physical Curve("contact") = {1};
Physical Curve("top") = {2};
Physical Curve("outer") = {3};
Physical Curve("bottom") = {4};
Physical Curve("axis") = {5};
Physical Surface("body") = {1};
Mesh.MshFileVersion = 4.1;
