// The paper's Example 7.1 body, Ω = [0,12]×[0,2] (length unit of the case), unstructured.
// Γ1 = clamp (x = 0 and x = 12), Γ2 = Γa = load (top and the bottom ends), Γ3 = contact
// ([2,10]×{0}). Regenerate with: gmsh -2 -format msh41 paper-rectangle.geo
h = 0.5;
Point(1) = {0, 0, 0, h};
Point(2) = {2, 0, 0, h};
Point(3) = {10, 0, 0, h};
Point(4) = {12, 0, 0, h};
Point(5) = {12, 2, 0, h};
Point(6) = {0, 2, 0, h};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 6};
Line(6) = {6, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};
Physical Curve("clamp") = {4, 6};
Physical Curve("load") = {5, 1, 3};
Physical Curve("contact") = {2};
Physical Surface("body") = {1};
Mesh.MshFileVersion = 4.1;
