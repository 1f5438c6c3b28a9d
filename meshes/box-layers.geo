// The box [0,2]×[0,1]×[0,1] in two layers (z below and above 0.5), coarse tetrahedra: each
// outer face a group of its own (x0, x1, y0, y1, bottom at z = 0, top at z = 1), the plane
// z = 0.5 between the layers a group inside the body ("middle": an electrode between two
// layers), the layers the volumes "lower" and "upper".
// Regenerate with: gmsh -3 -format msh41 box-layers.geo
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 2, 1, 0.5};
Box(2) = {0, 0, 0.5, 2, 1, 0.5};
BooleanFragments{ Volume{1}; Delete; }{ Volume{2}; Delete; }
Mesh.CharacteristicLengthMax = 0.35;
e = 1e-6;
Physical Surface("x0") = Surface In BoundingBox{-e, -e, -e, e, 1 + e, 1 + e};
Physical Surface("x1") = Surface In BoundingBox{2 - e, -e, -e, 2 + e, 1 + e, 1 + e};
Physical Surface("y0") = Surface In BoundingBox{-e, -e, -e, 2 + e, e, 1 + e};
Physical Surface("y1") = Surface In BoundingBox{-e, 1 - e, -e, 2 + e, 1 + e, 1 + e};
Physical Surface("bottom") = Surface In BoundingBox{-e, -e, -e, 2 + e, 1 + e, e};
Physical Surface("top") = Surface In BoundingBox{-e, -e, 1 - e, 2 + e, 1 + e, 1 + e};
Physical Surface("middle") = Surface In BoundingBox{-e, -e, 0.5 - e, 2 + e, 1 + e, 0.5 + e};
Physical Volume("lower") = Volume In BoundingBox{-e, -e, -e, 2 + e, 1 + e, 0.5 + e};
Physical Volume("upper") = Volume In BoundingBox{-e, -e, 0.5 - e, 2 + e, 1 + e, 1 + e};
Mesh.MshFileVersion = 4.1;
