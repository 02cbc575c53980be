// Meshes a gmsh .geo file through gmsh's API (Debian 12 has libgmsh but no gmsh program), as `gmsh -DIM FILE.geo
// -format msh41 -setnumber NAME VALUE ... -o OUT.msh` would. Not built by CMake:
//   g++ -std=c++17 mesh_geo.cpp -lgmsh -o mesh_geo
//   ./mesh_geo FILE.geo DIM OUT.msh [-setnumber NAME VALUE ...]
// The options after OUT.msh go to gmsh::initialize as on gmsh's command line (-setnumber overrides a DefineConstant).
#include <gmsh.h>

#include <string>
#include <vector>

int main(int argc, char** argv) {
  if (argc < 4) return 2;
  std::vector<char*> options{argv[0]};
  for (int i = 4; i < argc; ++i) options.push_back(argv[i]);
  gmsh::initialize(int(options.size()), options.data());
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::open(argv[1]);
  gmsh::model::mesh::generate(std::stoi(argv[2]));
  gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
  gmsh::write(argv[3]);
  gmsh::finalize();
}
