// A unit square of quadrilaterals: piezocontact must refuse it with a clear message.
// Regenerate with: gmsh -2 -format msh41 quads.geo
Point(1) = {0, 0, 0, 0.5}; Point(2) = {1, 0, 0, 0.5}; Point(3) = {1, 1, 0, 0.5}; Point(4) = {0, 1, 0, 0.5};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1}; Recombine Surface{1};
Physical Curve("bottom") = {1}; Physical Surface("body") = {1};
