// A block on a curved contact face: top y = 2, sides x = 0 and x = 4, bottom the circular
// arc through (0, 0.5), (2, 0), (4, 0.5) (centre (2, 4.25), radius 4.25).
// Regenerate with: gmsh -2 -format msh41 -bin arch.geo
h = 0.25;
Point(1) = {0, 0.5, 0, h};
Point(2) = {4, 0.5, 0, h};
Point(3) = {4, 2, 0, h};
Point(4) = {0, 2, 0, h};
Point(5) = {2, 4.25, 0, h};
Circle(1) = {1, 5, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Curve("clamp") = {2, 4};
Physical Curve("top") = {3};
Physical Curve("contact") = {1};
Physical Surface("body") = {1};
Mesh.MshFileVersion = 4.1;
Mesh.Binary = 1;
