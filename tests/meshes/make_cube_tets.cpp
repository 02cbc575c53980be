// Writes the unit-cube tetrahedral meshes of tests/meshes (order 1 or 2, argument 1) to the file of argument 2,
// with a physical volume "cube" and a physical surface "bottom" (z = 0). Not built by CMake: see README.md.
#include <gmsh.h>
#include <string>
int main(int argc, char** argv) {
  const int order = std::stoi(argv[1]);
  const std::string out = argv[2];
  gmsh::initialize();
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::model::add("cube");
  gmsh::model::occ::addBox(0, 0, 0, 1, 1, 1, 1);
  gmsh::model::occ::synchronize();
  gmsh::option::setNumber("Mesh.MeshSizeMax", 0.5);
  gmsh::model::addPhysicalGroup(3, {1}, 1);
  gmsh::model::setPhysicalName(3, 1, "cube");
  // the face z = 0 of OCC's box is surface 5
  std::vector<std::pair<int, int>> faces;
  gmsh::model::getEntities(faces, 2);
  for (auto [dim, tag] : faces) {
    double xmin, ymin, zmin, xmax, ymax, zmax;
    gmsh::model::getBoundingBox(dim, tag, xmin, ymin, zmin, xmax, ymax, zmax);
    if (zmax < 1e-6) { gmsh::model::addPhysicalGroup(2, {tag}, 2); gmsh::model::setPhysicalName(2, 2, "bottom"); }
  }
  gmsh::model::mesh::generate(3);
  if (order == 2) gmsh::model::mesh::setOrder(2);
  gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
  gmsh::write(out);
  gmsh::finalize();
}
