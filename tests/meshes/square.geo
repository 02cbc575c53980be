// The unit square of the mesh-import tests (tests/meshes/README.md says how each .msh was made): 4 x 4
// transfinite cells cut into triangles, physical curves on its sides (and one group of two of them) and a point
// at its top-right corner.
DefineConstant[ order = 1, quads = 0 ];
Point(1) = {0, 0, 0};
Point(2) = {1, 0, 0};
Point(3) = {1, 1, 0};
Point(4) = {0, 1, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 2, 3, 4} = 5;
Transfinite Surface{1} = {1, 2, 3, 4} Right;  // diagonals along +x+y: the corner cell at (1, 0) has all three corners on "bottom_right"
If (quads)
  Recombine Surface{1};
EndIf
Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
Physical Curve("bottom_right") = {1, 2};  // two curves meeting at a corner cell
Physical Point("corner") = {3};
Physical Surface("square") = {1};
Mesh.ElementOrder = order;
