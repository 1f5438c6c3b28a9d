// A unit cube whose body has no Physical Volume: Gmsh saves only the triangles of its
// physical surfaces, and piezocontact must say that the volume is missing.
// Regenerate with: gmsh -3 -format msh41 no-volume.geo
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Mesh.CharacteristicLengthMax = 1;
Physical Surface("bottom") = {5};
Physical Surface("top") = {6};
