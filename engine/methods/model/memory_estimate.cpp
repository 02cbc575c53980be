#include "engine/methods/model/memory_estimate.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "engine/core/errors.hpp"

namespace loom {
namespace {

// Mesh files are not estimated here. 3D: six tetrahedra per cube of a box or per extruded square.
double cells_of(const MeshSpec& m) {
  if (m.generator == MeshGenerator::box) return 6.0 * double(m.nx) * double(m.ny) * double(m.nz);
  if (m.depth > 0.0) return 6.0 * double(m.nx) * double(m.ny) * double(m.layers);
  return (m.quads ? 1.0 : 2.0) * double(m.nx) * double(m.ny);
}

// Bytes per cell at n cells (see the header): the measured figure at 8e4 cells, 8 % more per doubling.
double per_cell(Formulation f, double n) {
  double base = 1.5e3;  // p1
  switch (f) {
    case Formulation::tri6: base = 8.5e3; break;
    case Formulation::p1p1_uphi: case Formulation::p1p1_up: base = 5.5e3; break;
    case Formulation::es_up: base = 15e3; break;  // 1.85x the couplings of p1p1_uphi, and more fill
    case Formulation::fem_up: base = 5.8e3; break;
    case Formulation::es_u: base = 4.2e3; break;
    case Formulation::fem_u: base = 2.5e3; break;
    case Formulation::quad9: base = 19e3; break;  // about two tri6 cells' dofs, 18 x 18 couplings (not yet measured)
    default: break;
  }
  return base * (1.0 + 0.08 * std::max(0.0, std::log2(n / 8e4)));
}

// A line "Key:   value kB" of a /proc file, in bytes; -1 if absent.
double proc_kb(const char* file, const std::string& key) {
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);)
    if (line.rfind(key + ":", 0) == 0) return 1024.0 * std::stod(line.substr(key.size() + 1));
  return -1.0;
}

std::string gb(double bytes) {
  std::ostringstream os;
  os.precision(bytes < 1e9 ? 2 : 3);
  os << bytes / 1e9 << " GB";
  return os.str();
}

}  // namespace

MemoryEstimate estimate_memory(const SceneSpec& scene) {
  MemoryEstimate e;
  if (is_mpm(scene.scene.method)) {
    const BodySpec& body = scene.bodies.at(0);
    const double particles = cells_of(body.mesh) * body.particles_per_cell;
    const double grid = scene.grid.quad4 ? double(scene.grid.mesh.nx) * scene.grid.mesh.ny : cells_of(scene.grid.mesh);
    // Grid geometry and particle columns, and the system over the active cells (at most one per particle).
    e.cells = grid;
    const double active = std::min(grid, particles), system = body.element == Formulation::p1p1_up ? 3.0e3 : 1.5e3;
    e.bytes = 300.0 * grid + 400.0 * particles + system * active;
    return e;
  }
  for (const auto& b : scene.bodies) e.cells += cells_of(b.mesh);
  for (const auto& b : scene.bodies) e.bytes += per_cell(b.element, e.cells) * cells_of(b.mesh);
  return e;
}

double available_memory(std::string* why) {
  double available = proc_kb("/proc/meminfo", "MemAvailable");
  if (why) *why = "the memory this machine has available";
  struct rlimit limit {};
  if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
    const double used = std::max(0.0, proc_kb("/proc/self/status", "VmSize"));
    const double left = double(limit.rlim_cur) - used;
    if (available < 0 || left < available) {
      available = left;
      if (why) *why = "what the address-space limit of the process (ulimit -v) leaves";
    }
  }
  return available;
}

void check_memory(const SceneSpec& scene) {
  const MemoryEstimate e = estimate_memory(scene);
  std::string why;
  const double available = available_memory(&why);
  if (available < 0 || e.bytes <= available) return;
  // Name the mesh with the most cells.
  const MeshSpec* mesh = &scene.bodies.at(0).mesh;
  std::string key = "body[0].mesh.divisions";
  for (std::size_t b = 0; b < scene.bodies.size(); ++b)
    if (cells_of(scene.bodies[b].mesh) > cells_of(*mesh)) mesh = &scene.bodies[b].mesh, key = "body[" + std::to_string(b) + "].mesh.divisions";
  if (is_mpm(scene.scene.method) && scene.grid.present && cells_of(scene.grid.mesh) > cells_of(*mesh))
    mesh = &scene.grid.mesh, key = "grid.divisions";
  // The divisions as the scene gives them: three numbers for a box, the layers of an extrusion under their own key.
  std::ostringstream divisions;
  divisions << "[" << mesh->nx << ", " << mesh->ny;
  if (mesh->generator == MeshGenerator::box) divisions << ", " << mesh->nz;
  divisions << "]";
  if (mesh->generator != MeshGenerator::box && mesh->depth > 0.0) divisions << " with " << mesh->layers << " layers";
  std::ostringstream os;
  os.precision(3);
  os << mesh->where << ": error: " << key << ": " << divisions.str() << " makes about " << e.cells
     << " cells; the run would need about " << gb(e.bytes) << " of memory, and " << gb(available) << " are available (" << why
     << "); use fewer divisions";
  throw InputError(os.str());
}

}  // namespace loom
