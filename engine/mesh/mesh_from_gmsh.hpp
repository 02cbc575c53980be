// The triangles of a two-dimensional body from a gmsh file (engine/mesh/gmsh_file.hpp): its 3- or 6-node
// triangles (those of one physical surface when `surface` is given), in the plane z = 0, counter-clockwise,
// corners numbered first; the file's physical groups as named regions of corner nodes.
//
// Errors (InputError "<where>: error: <key>: <file>: ..."): no triangles, other element types (quadrangles,
// 10-node triangles, volume elements), nodes off the plane, a surface that does not exist, and cells that
// are inverted or of zero area (named by their element tag in the file).
#pragma once

#include <string>

#include "engine/mesh/gmsh_file.hpp"
#include "engine/mesh/mesh_data.hpp"

namespace loom {

MeshData triangle_mesh_of(const GmshFile& file, const std::string& surface, const std::string& where, const std::string& key);

}  // namespace loom
