// A quarter of a plate with a circular hole, for scenes/plate_with_hole.toml: the hole (radius a) at the
// origin, the plate 2L long (along the load, x) and 2W wide, so d/W = 2a/2W = 0.1. Symmetry lines x = 0
// ("left") and y = 0 ("bottom"); the load on x = L ("right"). 6-node triangles, their mid-nodes on the arc.
// Mesh sizes: h_hole on the hole, h_far at the far corners. The committed meshes:
//   gmsh -2 plate_with_hole.geo -format msh41 -setnumber h_hole 0.2  -o plate_with_hole_coarse.msh
//   gmsh -2 plate_with_hole.geo -format msh41 -setnumber h_hole 0.1  -o plate_with_hole.msh
//   gmsh -2 plate_with_hole.geo -format msh41 -setnumber h_hole 0.05 -o plate_with_hole_fine.msh
DefineConstant[ h_hole = 0.1, h_far = 2.0 ];
a = 1.0;   // hole radius
W = 10.0;  // half width
L = 20.0;  // half length (along the load)
Point(1) = {0, 0, 0, h_hole};
Point(2) = {a, 0, 0, h_hole};
Point(3) = {L, 0, 0, h_far};
Point(4) = {L, W, 0, h_far};
Point(5) = {0, W, 0, h_far};
Point(6) = {0, a, 0, h_hole};
Line(1) = {2, 3};
Line(2) = {3, 4};
Line(3) = {4, 5};
Line(4) = {5, 6};
Circle(5) = {6, 1, 2};
Curve Loop(1) = {1, 2, 3, 4, 5};
Plane Surface(1) = {1};
Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
Physical Curve("hole") = {5};
Physical Point("A") = {6};  // top of the hole: sigma_xx = K_t * sigma
Physical Point("B") = {2};  // side of the hole: sigma_yy = -sigma (Kirsch)
Physical Surface("plate") = {1};
Mesh.ElementOrder = 2;
Mesh.HighOrderOptimize = 0;
