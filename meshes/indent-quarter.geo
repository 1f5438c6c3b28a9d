// A quarter of the indentation block of indent-3d.geo: [0,1]x[0,1]x[-1,0], the top face split
// into the contact patch [0,rc]^2 x {0} and the rest, the mesh refined toward the origin. The
// planes x = 0 (sym_x) and y = 0 (sym_y) are the block's symmetry planes; sides are x = 1 and
// y = 1. hc is the element size at the origin. mirror-quarter.py mirrors a quarter mesh about
// both planes into the full block (indent-full-hH.msh), node for node.
// Regenerate with: gmsh -3 -setnumber hc H indent-quarter.geo -o indent-quarter-hH.msh (H = 0.05, 0.03;
// the bench pair with -setnumber hc 0.015 -setnumber hf 0.15), then
// python3 mirror-quarter.py indent-quarter-hH.msh indent-full-hH.msh; the quarter turned by 30°
// about z: python3 mirror-quarter.py --turn 30 indent-quarter-h0.05.msh indent-quarter-turned-h0.05.msh
SetFactory("OpenCASCADE");
DefineConstant[ hc = 0.03, hf = 0.3, rc = 0.3 ];
Box(1) = {0, 0, -1, 1, 1, 1};
Rectangle(10) = {0, 0, 0, rc, rc};
BooleanFragments{ Volume{1}; Delete; }{ Surface{10}; Delete; }
Point(100) = {0, 0, 0};
Field[1] = Distance; Field[1].PointsList = {100};
Field[2] = Threshold; Field[2].InField = 1; Field[2].SizeMin = hc; Field[2].SizeMax = hf;
Field[2].DistMin = 0.2; Field[2].DistMax = 1.2;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0; Mesh.MeshSizeFromPoints = 0; Mesh.MeshSizeFromCurvature = 0;
e = 1e-6;
Physical Surface("contact") = Surface In BoundingBox{-e, -e, -e, rc + e, rc + e, e};
top() = Surface In BoundingBox{-e, -e, -e, 1 + e, 1 + e, e};
contact() = Surface In BoundingBox{-e, -e, -e, rc + e, rc + e, e};
Physical Surface("top") = {top()};
Physical Surface("top") -= {contact()};
Physical Surface("bottom") = Surface In BoundingBox{-e, -e, -1 - e, 1 + e, 1 + e, -1 + e};
Physical Surface("sides") = {Surface In BoundingBox{1 - e, -e, -1 - e, 1 + e, 1 + e, e}, Surface In BoundingBox{-e, 1 - e, -1 - e, 1 + e, 1 + e, e}};
Physical Surface("sym_x") = Surface In BoundingBox{-e, -e, -1 - e, e, 1 + e, e};
Physical Surface("sym_y") = Surface In BoundingBox{-e, -e, -1 - e, 1 + e, e, e};
Physical Volume("body") = {Volume{:}};
Mesh.MshFileVersion = 4.1;
Mesh.Binary = 1;
