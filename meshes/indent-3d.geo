// A block [-1,1]x[-1,1]x[-1,0] for 3D indentation by a rigid sphere: the top face split into
// the contact patch [-rc,rc]^2 x {0} and the rest, the mesh refined toward the origin. hc is
// the element size at the origin.
// Regenerate with: gmsh -3 -setnumber hc H indent-3d.geo -o indent-3d-hH.msh (H = the size at the origin)
SetFactory("OpenCASCADE");
DefineConstant[ hc = 0.03, hf = 0.3, rc = 0.3 ];
Box(1) = {-1, -1, -1, 2, 2, 1};
Rectangle(10) = {-rc, -rc, 0, 2 * rc, 2 * rc};
BooleanFragments{ Volume{1}; Delete; }{ Surface{10}; Delete; }
Point(100) = {0, 0, 0};
Field[1] = Distance; Field[1].PointsList = {100};
Field[2] = Threshold; Field[2].InField = 1; Field[2].SizeMin = hc; Field[2].SizeMax = hf;
Field[2].DistMin = 0.2; Field[2].DistMax = 1.2;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0; Mesh.MeshSizeFromPoints = 0; Mesh.MeshSizeFromCurvature = 0;
e = 1e-6;
Physical Surface("contact") = Surface In BoundingBox{-rc - e, -rc - e, -e, rc + e, rc + e, e};
top() = Surface In BoundingBox{-1 - e, -1 - e, -e, 1 + e, 1 + e, e};
contact() = Surface In BoundingBox{-rc - e, -rc - e, -e, rc + e, rc + e, e};
Physical Surface("top") = {top()};
Physical Surface("top") -= {contact()};
Physical Surface("bottom") = Surface In BoundingBox{-1 - e, -1 - e, -1 - e, 1 + e, 1 + e, -1 + e};
Physical Surface("sides") = {Surface In BoundingBox{-1 - e, -1 - e, -1 - e, -1 + e, 1 + e, e}, Surface In BoundingBox{1 - e, -1 - e, -1 - e, 1 + e, 1 + e, e}, Surface In BoundingBox{-1 - e, -1 - e, -1 - e, 1 + e, -1 + e, e}, Surface In BoundingBox{-1 - e, 1 - e, -1 - e, 1 + e, 1 + e, e}};
Physical Volume("body") = {Volume{:}};
Mesh.MshFileVersion = 4.1;
Mesh.Binary = 1;
