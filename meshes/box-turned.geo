// The box [0,2]×[0,1]×[0,1] of box-faces.geo turned by 30° about the z axis, coarse
// tetrahedra, each face a group of its own, for rollers on turned faces: x0 and x1 (the
// faces x' = 0 and x' = 2 of the turned frame), y0, y1, bottom (z = 0), top (z = 1).
// Regenerate with: gmsh -3 -format msh41 box-turned.geo
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 2, 1, 1};
Rotate {{0, 0, 1}, {0, 0, 0}, Pi/6} { Volume{1}; }
Mesh.CharacteristicLengthMax = 0.35;
Physical Surface("x0") = {1};
Physical Surface("x1") = {2};
Physical Surface("y0") = {3};
Physical Surface("y1") = {4};
Physical Surface("bottom") = {5};
Physical Surface("top") = {6};
Physical Volume("body") = {1};
Mesh.MshFileVersion = 4.1;
