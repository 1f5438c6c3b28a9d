// A PZT block for 3D benchmarks: 2 × 2 × 1, about 100k tetrahedra.
// Regenerate with: gmsh -3 block-100k.geo -o block-100k.msh (binary MSH 4.1, ~4.9 MB)
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 2, 2, 1};
Mesh.CharacteristicLengthMax = 0.058;
Mesh.CharacteristicLengthMin = 0.058;
Physical Surface("bottom") = {5};
Physical Surface("top") = {6};
Physical Surface("sides") = {1, 2, 3, 4};
Physical Volume("body") = {1};
Mesh.MshFileVersion = 4.1;
Mesh.Binary = 1;
