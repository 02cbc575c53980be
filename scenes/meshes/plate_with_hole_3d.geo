// An eighth of a thick plate with a circular hole, for scenes/plate_with_hole_3d.toml: the quarter of
// plate_with_hole.geo (hole of radius a at the origin, 2L long along the load x, 2W wide) extruded along z through
// half the thickness T, in layers. Symmetry planes x = 0 ("left"), y = 0 ("bottom") and z = 0 ("front", the
// mid-plane); "back" the face z = T/2; the load on x = L ("right"). 10-node tetrahedra, their edge nodes on the hole.
// Debian 12 has libgmsh but no gmsh program: mesh_geo.cpp (beside this file) meshes it through the API.
//   ./mesh_geo plate_with_hole_3d.geo 3 plate_with_hole_3d.msh
DefineConstant[ h_hole = 0.1, h_far = 2.0, T = 1.0, layers = 2 ];
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
// out[0]: the face z = T/2, out[1]: the volume, out[2..6]: the faces swept by curves 1..5.
out[] = Extrude {0, 0, T / 2} { Surface{1}; Layers{layers}; };
Physical Surface("front") = {1};
Physical Surface("back") = {out[0]};
Physical Surface("bottom") = {out[2]};
Physical Surface("right") = {out[3]};
Physical Surface("top") = {out[4]};
Physical Surface("left") = {out[5]};
Physical Surface("hole") = {out[6]};
Physical Point("A") = {6};  // top of the hole on the mid-plane: sigma_xx = K_t * sigma
Physical Point("B") = {2};  // side of the hole on the mid-plane: sigma_yy = -sigma (Kirsch)
Physical Volume("plate") = {out[1]};
Mesh.ElementOrder = 2;
Mesh.HighOrderOptimize = 0;
