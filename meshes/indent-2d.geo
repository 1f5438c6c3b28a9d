// A block [-1,1]x[-1,0] for 2D indentation by a rigid disk (Hertz verification): bottom
// clamped, the top edge split into the contact segment [-rc, rc]x{0} and the rest, the mesh
// refined toward the origin. hc, the element size at the origin, is set from the command line.
// Regenerate with: gmsh -2 -setnumber hc H indent-2d.geo -o indent-2d-hH.msh (H = the size at the origin)
SetFactory("OpenCASCADE");
DefineConstant[ hc = 0.01, hf = 0.15, rc = 0.35 ];
Rectangle(1) = {-1, -1, 0, 2, 1};
Point(10) = {-rc, 0, 0};
Point(11) = {rc, 0, 0};
Point(12) = {0, 0, 0};
BooleanFragments{ Surface{1}; Delete; }{ Point{10, 11, 12}; Delete; }
Field[1] = Distance; Field[1].PointsList = {12};
Field[2] = Threshold; Field[2].InField = 1; Field[2].SizeMin = hc; Field[2].SizeMax = hf;
Field[2].DistMin = 0.15; Field[2].DistMax = 1.0;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0; Mesh.MeshSizeFromPoints = 0; Mesh.MeshSizeFromCurvature = 0;
e = 1e-6;
Physical Curve("contact") = Curve In BoundingBox{-rc - e, -e, -e, rc + e, e, e};
Physical Curve("top") = {Curve In BoundingBox{-1 - e, -e, -e, -rc + e, e, e}, Curve In BoundingBox{rc - e, -e, -e, 1 + e, e, e}};
Physical Curve("bottom") = Curve In BoundingBox{-1 - e, -1 - e, -e, 1 + e, -1 + e, e};
Physical Curve("sides") = {Curve In BoundingBox{-1 - e, -1 - e, -e, -1 + e, e, e}, Curve In BoundingBox{1 - e, -1 - e, -e, 1 + e, e, e}};
Physical Surface("body") = {Surface{:}};
Mesh.MshFileVersion = 4.1;
Mesh.Binary = 1;
