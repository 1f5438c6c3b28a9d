// The unit cube, coarse tetrahedra, for 3D tests: bottom (z = 0), top (z = 1), sides.
// Regenerate with: gmsh -3 -format msh41 cube.geo
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Mesh.CharacteristicLengthMax = 0.4;
Physical Surface("bottom") = {5};
Physical Surface("top") = {6};
Physical Surface("sides") = {1, 2, 3, 4};
Physical Volume("body") = {1};
Mesh.MshFileVersion = 4.1;
