// Writes the quarter solids of revolution of the 3D free-surface scenes as linear tetrahedra (gmsh's OpenCASCADE
// kernel; Debian 12 has libgmsh but no gmsh program): a quarter of a cone frustum about the z axis, its base on z = 0,
// in x >= 0 and y >= 0 (or, with SECTOR = 180, a half in y >= 0), with the physical volume "paste". Not built by CMake:
//   g++ -std=c++17 make_quarter_solids.cpp -lgmsh -o make_quarter_solids
//   ./make_quarter_solids R_BOTTOM R_TOP HEIGHT H_MAX OUT.msh [SECTOR_DEGREES, default 90]
// The committed meshes (README.md beside this file):
//   ./make_quarter_solids 0.05 0.05 0.1 0.01 quarter_cylinder_10mm.msh     (Pashias' column, 5 cells across)
//   ./make_quarter_solids 0.1 0.05 0.3 0.025 abrams_quarter_25mm.msh       (the Abrams cone)
//   ./make_quarter_solids 0.028 0.028 0.024 0.0093 print_plug_half_9mm.msh 180   (the printing nozzle's plug)
#include <gmsh.h>

#include <cmath>
#include <string>

int main(int argc, char** argv) {
  if (argc != 6 && argc != 7) return 2;
  const double sector = (argc == 7 ? std::stod(argv[6]) : 90.0) * M_PI / 180.0;
  const double r_bottom = std::stod(argv[1]), r_top = std::stod(argv[2]), height = std::stod(argv[3]), h = std::stod(argv[4]);
  gmsh::initialize();
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::model::add("quarter");
  if (r_bottom == r_top) gmsh::model::occ::addCylinder(0, 0, 0, 0, 0, height, r_bottom, 1, sector);
  else gmsh::model::occ::addCone(0, 0, 0, 0, 0, height, r_bottom, r_top, 1, sector);
  gmsh::model::occ::synchronize();
  gmsh::option::setNumber("Mesh.MeshSizeMax", h);
  gmsh::option::setNumber("Mesh.MeshSizeMin", h);
  gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
  gmsh::option::setNumber("Mesh.Optimize", 1);
  gmsh::model::addPhysicalGroup(3, {1}, 1);
  gmsh::model::setPhysicalName(3, 1, "paste");
  gmsh::model::mesh::generate(3);
  gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
  gmsh::write(argv[5]);
  gmsh::finalize();
}
