// The paper's bar in 3D, for benchmarks: 12 × 2 × 2, about 104k tetrahedra (20k nodes).
// Regenerate with: gmsh -3 bar-3d.geo -o bar-3d.msh (binary MSH 4.1, ~5.3 MB)
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 12, 2, 2};
Mesh.CharacteristicLengthMax = 0.13;
Mesh.CharacteristicLengthMin = 0.13;
Physical Surface("ends") = {1, 2};
Physical Surface("front_back") = {3, 4};
Physical Surface("bottom") = {5};
Physical Surface("top") = {6};
Physical Volume("body") = {1};
Mesh.MshFileVersion = 4.1;
Mesh.Binary = 1;
