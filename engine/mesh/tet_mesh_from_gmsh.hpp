// The tetrahedra of a three-dimensional body from a gmsh file (engine/mesh/gmsh_file.hpp): its 4- or 10-node
// tetrahedra (those of one physical volume when `volume` is given), corners numbered first in order of first use,
// then the 10-node cells' own mid-nodes (which may sit off the straight edges); gmsh's 10-node order (edges 01 12
// 20 30 32 31) turned into VTK_QUADRATIC_TETRA's (01 12 20 03 13 23). The file's physical groups become named
// regions of corner nodes.
//
// Errors (InputError "<where>: error: <key>: <file>: ..."): no tetrahedra, other volume elements (hexahedra,
// prisms, pyramids), a volume that does not exist, a mix of 4- and 10-node tetrahedra, and cells that are inverted
// or of zero volume (named by their element tag in the file).
#pragma once

#include <string>

#include "engine/mesh/gmsh_file.hpp"
#include "engine/mesh/tet_mesh.hpp"

namespace loom {

struct TetMeshFile {
  TetMeshData corners;      // the tet4 mesh of the corners (with regions and element tags)
  Tet10MeshData quadratic;  // 10-node files: the whole cells (corner numbering as `corners`); empty otherwise
  bool is_quadratic() const { return !quadratic.cells.empty(); }
};

TetMeshFile tet_mesh_of(const GmshFile& file, const std::string& volume, const std::string& where, const std::string& key);

}  // namespace loom
