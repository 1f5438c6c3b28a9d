// Two separate rectangles: [0,4]x[0,1], clamped and grounded on its left side, and a loose
// [5,6]x[0,1] that touches no clamped or grounded part. A mesh that `check` must refuse.
// Regenerate with: gmsh -2 two-bodies.geo -o two-bodies.msh
SetFactory("OpenCASCADE");
Rectangle(1) = {0, 0, 0, 4, 1};
Rectangle(2) = {5, 0, 0, 1, 1};
e = 1e-6;
Physical Curve("left") = Curve In BoundingBox{-e, -e, -e, e, 1 + e, e};
Physical Curve("bottom") = Curve In BoundingBox{-e, -e, -e, 6 + e, e, e};
Physical Surface("body") = {1, 2};
Mesh.MeshSizeMax = 0.5;
Mesh.MshFileVersion = 4.1;
