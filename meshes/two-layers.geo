// The box [0,2]×[0,1]×[0,1] in two layers, a substrate (z < 0.5) under a layer (z > 0.5)
// sharing the plane z = 0.5, coarse tetrahedra, for materials by region: volume groups
// "substrate" and "layer"; faces x0 (x = 0), x1 (x = 2), y0, y1, bottom (z = 0), top (z = 1),
// each lateral face holding both layers' facets.
// Regenerate with: gmsh -3 -format msh41 two-layers.geo
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 2, 1, 0.5};
Box(2) = {0, 0, 0.5, 2, 1, 0.5};
BooleanFragments{ Volume{1}; Delete; }{ Volume{2}; Delete; }
Mesh.CharacteristicLengthMax = 0.3;
e = 1e-6;
Physical Surface("x0") = Surface In BoundingBox{-e, -e, -e, e, 1 + e, 1 + e};
Physical Surface("x1") = Surface In BoundingBox{2 - e, -e, -e, 2 + e, 1 + e, 1 + e};
Physical Surface("y0") = Surface In BoundingBox{-e, -e, -e, 2 + e, e, 1 + e};
Physical Surface("y1") = Surface In BoundingBox{-e, 1 - e, -e, 2 + e, 1 + e, 1 + e};
Physical Surface("bottom") = Surface In BoundingBox{-e, -e, -e, 2 + e, 1 + e, e};
Physical Surface("top") = Surface In BoundingBox{-e, -e, 1 - e, 2 + e, 1 + e, 1 + e};
Physical Volume("substrate") = Volume In BoundingBox{-e, -e, -e, 2 + e, 1 + e, 0.5 + e};
Physical Volume("layer") = Volume In BoundingBox{-e, -e, 0.5 - e, 2 + e, 1 + e, 1 + e};
Mesh.MshFileVersion = 4.1;
