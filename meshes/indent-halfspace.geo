// A block [-4,4]² × [-4,0] standing for a half-space in indentation tests: the contact patch
// |x|, |y| ≤ rc of its top face is Γ3, and the element size grows linearly with the distance r
// from the origin, h = hc + g r, so that a contact disc of radius a ≪ 4 is resolved by about
// a/(hc + g a) elements at a few thousand nodes.
// The committed meshes (the tests of the classical indentation laws):
//   gmsh -3 -setnumber hc 0.004 -setnumber g 0.2 indent-halfspace.geo -o indent-halfspace-coarse.msh
//   gmsh -3 -setnumber hc 0.002 -setnumber g 0.15 indent-halfspace.geo -o indent-halfspace-fine.msh
SetFactory("OpenCASCADE");
DefineConstant[ hc = 0.002, g = 0.15, rc = 0.2, L = 4 ];
Box(1) = {-L, -L, -L, 2 * L, 2 * L, L};
Rectangle(10) = {-rc, -rc, 0, 2 * rc, 2 * rc};
BooleanFragments{ Volume{1}; Delete; }{ Surface{10}; Delete; }
Field[1] = MathEval;
Field[1].F = Sprintf("%g + %g * Sqrt(x^2 + y^2 + z^2)", hc, g);
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0; Mesh.MeshSizeFromPoints = 0; Mesh.MeshSizeFromCurvature = 0;
e = 1e-6;
Physical Surface("contact") = Surface In BoundingBox{-rc - e, -rc - e, -e, rc + e, rc + e, e};
top() = Surface In BoundingBox{-L - e, -L - e, -e, L + e, L + e, e};
contact() = Surface In BoundingBox{-rc - e, -rc - e, -e, rc + e, rc + e, e};
Physical Surface("top") = {top()};
Physical Surface("top") -= {contact()};
Physical Surface("bottom") = Surface In BoundingBox{-L - e, -L - e, -L - e, L + e, L + e, -L + e};
Physical Surface("sides") = {Surface In BoundingBox{-L - e, -L - e, -L - e, -L + e, L + e, e}, Surface In BoundingBox{L - e, -L - e, -L - e, L + e, L + e, e}, Surface In BoundingBox{-L - e, -L - e, -L - e, L + e, -L + e, e}, Surface In BoundingBox{-L - e, L - e, -L - e, L + e, L + e, e}};
Physical Volume("body") = {Volume{:}};
Mesh.MshFileVersion = 4.1;
Mesh.Binary = 1;
