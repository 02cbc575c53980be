// A mesh file written by gmsh (.msh, format 4.1 or 2.2, ASCII or binary), read through gmsh's own API, as it
// is: every node, every element block of any dimension with gmsh's element type, and every physical group
// with its name, dimension and nodes. Nothing here is two-dimensional: turning it into the triangles of a
// body is mesh_from_gmsh's job, and tet_mesh_from_gmsh's for the tetrahedra of a 3D body.
//
// libgmsh is loaded when a file is read (dlopen of its C API, gmshc.h), not linked: linked, it loads 91
// shared libraries (OpenCASCADE, FLTK, ...) into every loom process, 70 ms and 48 MB before main, for
// the scenes that read no mesh file too.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <unordered_set>
#include <vector>

#include "engine/core/types.hpp"

namespace loom {

struct GmshElementBlock {
  int type = 0;            // gmsh element type: 2 = 3-node triangle, 9 = 6-node triangle, 4 = tetrahedron, ...
  std::string name;        // gmsh's name of the type ("Triangle 6")
  int dim = 0;
  int nodes_per_element = 0;
  std::vector<std::size_t> tags;  // element tags in the file
  std::vector<Index> nodes;       // indices into GmshFile::nodes, nodes_per_element per element (gmsh's order)
};

struct GmshGroup {
  int dim = 0;
  int tag = 0;
  std::string name;          // the physical name; "<tag>" when the group has none
  std::vector<Index> nodes;  // indices into GmshFile::nodes
};

struct GmshFile {
  std::string path;
  std::vector<std::array<double, 3>> nodes;
  std::vector<GmshElementBlock> blocks;
  std::vector<GmshGroup> groups;
  // The element tags of the physical groups' elements of dimension `dim` (for the body's group).
  std::vector<std::vector<std::size_t>> group_elements;  // parallel to groups
};

// Throws InputError "<where>: error: <key>: <path>: ..." if the file is missing or cannot be read, or
// libgmsh is not installed.
GmshFile read_gmsh_file(const std::string& path, const std::string& where, const std::string& key);

// The element tags of the physical group `name` of dimension `dim` (a body's surface or volume); an empty set for
// an empty name (every element). Throws InputError "<where>: error: <key>: <path>: no physical <kind> named ..."
// listing the file's groups if there is no such group.
std::unordered_set<std::size_t> elements_of_group(const GmshFile& file, const std::string& name, int dim, const std::string& where,
                                                  const std::string& key);

}  // namespace loom
