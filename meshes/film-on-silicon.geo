// A PZT film 10 µm thick on a silicon substrate, for indentation by a rigid ball: the block
// [-100,100]² × [-100,0] µm, the film z > −10 µm ("film"), the substrate below ("substrate");
// the top face split into the contact patch [-rc,rc]² × {0} and the rest ("top"), the bottom
// "bottom", the four sides "sides"; the mesh refined toward the origin (hc, the size there).
// Regenerate with: gmsh -3 film-on-silicon.geo -o film-on-silicon.msh
SetFactory("OpenCASCADE");
DefineConstant[ hc = 1.5, hf = 30, rc = 30, t = 10 ];
Box(1) = {-100, -100, -100, 200, 200, 100 - t};
Box(2) = {-100, -100, -t, 200, 200, t};
Rectangle(100) = {-rc, -rc, 0, 2 * rc, 2 * rc};
BooleanFragments{ Volume{1, 2}; Delete; }{ Surface{100}; Delete; }
Point(1000) = {0, 0, 0};
Field[1] = Distance; Field[1].PointsList = {1000};
Field[2] = Threshold; Field[2].InField = 1; Field[2].SizeMin = hc; Field[2].SizeMax = hf;
Field[2].DistMin = 20; Field[2].DistMax = 120;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0; Mesh.MeshSizeFromPoints = 0; Mesh.MeshSizeFromCurvature = 0;
e = 1e-3;
Physical Surface("contact") = Surface In BoundingBox{-rc - e, -rc - e, -e, rc + e, rc + e, e};
top() = Surface In BoundingBox{-100 - e, -100 - e, -e, 100 + e, 100 + e, e};
contact() = Surface In BoundingBox{-rc - e, -rc - e, -e, rc + e, rc + e, e};
Physical Surface("top") = {top()};
Physical Surface("top") -= {contact()};
Physical Surface("bottom") = Surface In BoundingBox{-100 - e, -100 - e, -100 - e, 100 + e, 100 + e, -100 + e};
Physical Surface("sides") = {Surface In BoundingBox{-100 - e, -100 - e, -100 - e, -100 + e, 100 + e, e}, Surface In BoundingBox{100 - e, -100 - e, -100 - e, 100 + e, 100 + e, e}, Surface In BoundingBox{-100 - e, -100 - e, -100 - e, 100 + e, -100 + e, e}, Surface In BoundingBox{-100 - e, 100 - e, -100 - e, 100 + e, 100 + e, e}};
Physical Volume("substrate") = Volume In BoundingBox{-100 - e, -100 - e, -100 - e, 100 + e, 100 + e, -t + e};
Physical Volume("film") = Volume In BoundingBox{-100 - e, -100 - e, -t - e, 100 + e, 100 + e, e};
Mesh.MshFileVersion = 4.1;
Mesh.Binary = 1;
