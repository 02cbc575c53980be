#include "engine/scene/mesh_options.hpp"

#include <filesystem>
#include <string>

namespace loom {

// A mesh file: its path relative to the scene file (or to the working directory when given by --set);
// the generators' keys do not apply.
void read_mesh_file(const TableReader& mesh, MeshSpec& m) {
  m.generator = MeshGenerator::file;
  m.file_where = mesh.where("file");
  const std::string file = mesh.string("file");
  const std::filesystem::path path(file);
  m.file = path.is_absolute() || m.file_where.line == 0 || m.file_where.file.empty()
               ? file
               : (std::filesystem::path(m.file_where.file).parent_path() / path).lexically_normal().string();
  if (file.empty()) mesh.error("file", "must not be empty");
  m.surface = mesh.string("group");
  m.scale = mesh.real("scale");
  for (const char* k : {"generator", "divisions", "origin", "size", "pattern", "distortion", "seed", "lattice"})
    if (mesh.has(k)) mesh.error(k, std::string(k) + " belongs to the generators; a mesh file takes file, group and scale");
}

void read_grid(const TableReader& grid, GridSpec& g) {
  read_mesh(grid, g.mesh);
  g.quad4 = grid.string("cells") == "quad4";
  g.quad9 = grid.string("cells") == "quad9";
  g.ghost_penalty = grid.has("ghost_penalty") ? grid.real("ghost_penalty") : g.quad4 ? 0.1 : 0.0;
  g.grading = grid.vec2("grading");
  g.refinements = int(grid.integer("refinements"));
  for (const char* k : {"grading", "refinements"})
    if (grid.has(k) && !g.quad9) grid.error(k, std::string(k) + " shapes quad9 grids (cells = \"quad9\")");
  if (g.quad9 && !(g.grading.minCoeff() > 0.0)) grid.error("grading", "the grading ratios must be > 0");
  if (g.quad9 && g.mesh.nx * double(g.mesh.ny) * double(1 << (2 * g.refinements)) > 5e7)
    grid.error("refinements", "more than 5e7 cells requested");
  if (!g.quad4 && !g.quad9) return;
  const char* cells = g.quad4 ? "cells = \"quad4\"" : "cells = \"quad9\"";
  if (g.mesh.generator != MeshGenerator::rectangle) grid.error("cells", std::string(cells) + " needs generator = \"rectangle\"");
  if (g.mesh.pattern != GridPattern::right) grid.error("pattern", std::string(cells) + " are quadrilaterals, not triangulated: leave pattern out");
  if (g.mesh.distortion != 0.0) grid.error("distortion", std::string(cells) + " are axis-aligned rectangles: distortion must be 0");
}

void read_mesh(const TableReader& mesh, MeshSpec& m) {
  m.where = mesh.where();
  m.key = mesh.path();
  if (mesh.present() && mesh.has("file")) {
    read_mesh_file(mesh, m);
    return;
  }
  if (mesh.has("group")) mesh.error("group", "group selects a physical surface of a mesh file: it needs file");
  m.generator = mesh.string("generator") == "cooks_membrane" ? MeshGenerator::cooks_membrane : MeshGenerator::rectangle;
  const auto div = mesh.ivec2("divisions");
  m.nx = int(div[0]), m.ny = int(div[1]);
  if (mesh.has("divisions") && (div[0] < 1 || div[1] < 1)) mesh.error("divisions", "divisions must be >= 1");
  if (mesh.has("divisions") && double(div[0]) * double(div[1]) > 5e7) mesh.error("divisions", "more than 5e7 cells requested");
  const std::string pattern = mesh.string("pattern");  // one of these after schema validation
  m.pattern = pattern == "alternating" ? GridPattern::alternating : pattern == "shifted" ? GridPattern::shifted : GridPattern::right;
  m.scale = mesh.real("scale");
  m.distortion = mesh.real("distortion");
  m.seed = mesh.integer("seed");
  if (m.generator == MeshGenerator::rectangle) {
    m.origin = mesh.vec2("origin");
    if (mesh.present() && !mesh.has("size")) mesh.error("", "missing required key size (for generator = \"rectangle\")");
    m.size = mesh.vec2("size");
    if (mesh.has("size") && (m.size.x() <= 0 || m.size.y() <= 0)) mesh.error("size", "width and height must be > 0");
  } else {
    for (const char* k : {"origin", "size"})
      if (mesh.has(k)) mesh.error(k, std::string(k) + " is not used by generator = \"cooks_membrane\" (use scale)");
  }
}

}  // namespace loom
