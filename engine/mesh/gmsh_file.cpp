#include "engine/mesh/gmsh_file.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <filesystem>
#include <mutex>
#include <sstream>
#include <unordered_map>

#include "engine/core/errors.hpp"

namespace loom {
namespace {

// The part of gmsh's C API (gmshc.h) the reader uses, resolved from the shared library at run time.
struct GmshApi {
  void (*free)(void*);
  void (*initialize)(int, char**, int, int*);
  void (*finalize)(int*);
  void (*option_set_number)(const char*, double, int*);
  void (*open)(const char*, int*);
  void (*last_error)(char**, int*);
  void (*physical_groups)(int**, std::size_t*, int, int*);
  void (*physical_name)(int, int, char**, int*);
  void (*entities_for_group)(int, int, int**, std::size_t*, int*);
  void (*nodes)(std::size_t**, std::size_t*, double**, std::size_t*, double**, std::size_t*, int, int, int, int, int*);
  void (*nodes_for_group)(int, int, std::size_t**, std::size_t*, double**, std::size_t*, int*);
  void (*elements)(int**, std::size_t*, std::size_t***, std::size_t**, std::size_t*, std::size_t***, std::size_t**, std::size_t*, int, int,
                   int*);
  void (*element_properties)(int, char**, int*, int*, int*, double**, std::size_t*, int*, int*);
};

template <class F>
void bind(void* lib, F& f, const char* name, std::string& missing) {
  f = reinterpret_cast<F>(dlsym(lib, name));
  if (!f) missing += std::string(missing.empty() ? "" : ", ") + name;
}

// Loaded once; nullptr and `why` set if libgmsh cannot be loaded.
const GmshApi* gmsh_api(std::string& why) {
  static GmshApi api;
  static std::string error;
  static const bool loaded = [] {
    void* lib = nullptr;
    for (const char* name : {LOOM_GMSH_LIBRARY, "libgmsh.so", "libgmsh.so.4.8"})
      if (*name && (lib = dlopen(name, RTLD_NOW | RTLD_LOCAL))) break;
    if (!lib) {
      const char* why = dlerror();  // a second call would return null
      error = "cannot load libgmsh (" + std::string(why ? why : "not found") + "): install it with apt install libgmsh-dev";
      return false;
    }
    std::string missing;
    bind(lib, api.free, "gmshFree", missing);
    bind(lib, api.initialize, "gmshInitialize", missing);
    bind(lib, api.finalize, "gmshFinalize", missing);
    bind(lib, api.option_set_number, "gmshOptionSetNumber", missing);
    bind(lib, api.open, "gmshOpen", missing);
    bind(lib, api.last_error, "gmshLoggerGetLastError", missing);
    bind(lib, api.physical_groups, "gmshModelGetPhysicalGroups", missing);
    bind(lib, api.physical_name, "gmshModelGetPhysicalName", missing);
    bind(lib, api.entities_for_group, "gmshModelGetEntitiesForPhysicalGroup", missing);
    bind(lib, api.nodes, "gmshModelMeshGetNodes", missing);
    bind(lib, api.nodes_for_group, "gmshModelMeshGetNodesForPhysicalGroup", missing);
    bind(lib, api.elements, "gmshModelMeshGetElements", missing);
    bind(lib, api.element_properties, "gmshModelMeshGetElementProperties", missing);
    if (!missing.empty()) error = "libgmsh lacks " + missing + " (gmsh 4.8 or later is needed)";
    return missing.empty();
  }();
  why = error;
  return loaded ? &api : nullptr;
}

// gmsh allocates the arrays it returns; they go back with gmshFree.
template <class T>
struct Owned {
  const GmshApi& api;
  T* p = nullptr;
  std::size_t n = 0;
  ~Owned() {
    if (p) api.free(p);
  }
};

std::string take_string(const GmshApi& api, char* s) {
  std::string r = s ? s : "";
  if (s) api.free(s);
  return r;
}

}  // namespace

GmshFile read_gmsh_file(const std::string& path, const std::string& where, const std::string& key) {
  auto fail = [&](const std::string& why) { throw InputError(where + ": error: " + key + ": " + path + ": " + why); };
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) fail("no such file");
  std::string why;
  const GmshApi* api = gmsh_api(why);
  if (!api) fail(why);
  const GmshApi& g = *api;

  static std::mutex gmsh_state;  // gmsh keeps one global model
  std::lock_guard<std::mutex> lock(gmsh_state);
  int ierr = 0;
  g.initialize(0, nullptr, 0, &ierr);
  struct Finalize {
    const GmshApi& g;
    ~Finalize() {
      int e = 0;
      g.finalize(&e);
    }
  } finalize{g};
  g.option_set_number("General.Terminal", 0, &ierr);  // loom reports errors itself
  g.open(path.c_str(), &ierr);
  if (ierr) {
    char* msg = nullptr;
    int e = 0;
    g.last_error(&msg, &e);
    std::string text = take_string(g, msg);
    fail("gmsh cannot read it" + (text.empty() ? std::string() : ": " + text));
  }

  GmshFile file;
  file.path = path;
  // Nodes: every node of the model, numbered by tag.
  std::unordered_map<std::size_t, Index> index_of;
  {
    Owned<std::size_t> tags{g};
    Owned<double> coord{g}, param{g};
    g.nodes(&tags.p, &tags.n, &coord.p, &coord.n, &param.p, &param.n, -1, -1, 0, 0, &ierr);
    if (ierr) fail("its nodes cannot be read");
    if (tags.n == 0) fail("it holds no mesh (a .geo must be meshed first: gmsh -2 part.geo -format msh41)");
    file.nodes.resize(tags.n);
    for (std::size_t k = 0; k < tags.n; ++k) {
      index_of[tags.p[k]] = Index(k);
      file.nodes[k] = {coord.p[3 * k], coord.p[3 * k + 1], coord.p[3 * k + 2]};
    }
  }
  auto node_index = [&](std::size_t tag) {
    auto it = index_of.find(tag);
    if (it == index_of.end()) fail("an element refers to node " + std::to_string(tag) + ", which the file does not define");
    return it->second;
  };
  // Element blocks of every dimension.
  {
    Owned<int> types{g};
    std::size_t** etags = nullptr;
    std::size_t* etags_n = nullptr;
    std::size_t etags_nn = 0;
    std::size_t** enodes = nullptr;
    std::size_t* enodes_n = nullptr;
    std::size_t enodes_nn = 0;
    g.elements(&types.p, &types.n, &etags, &etags_n, &etags_nn, &enodes, &enodes_n, &enodes_nn, -1, -1, &ierr);
    if (ierr) fail("its elements cannot be read");
    // Copied out and freed before anything can throw.
    std::vector<std::vector<std::size_t>> node_tags(types.n);
    for (std::size_t b = 0; b < types.n; ++b) {
      GmshElementBlock block;
      block.type = types.p[b];
      block.tags.assign(etags[b], etags[b] + etags_n[b]);
      node_tags[b].assign(enodes[b], enodes[b] + enodes_n[b]);
      file.blocks.push_back(std::move(block));
    }
    for (std::size_t b = 0; b < etags_nn; ++b) g.free(etags[b]);
    for (std::size_t b = 0; b < enodes_nn; ++b) g.free(enodes[b]);
    g.free(etags), g.free(etags_n), g.free(enodes), g.free(enodes_n);
    for (std::size_t b = 0; b < file.blocks.size(); ++b) {
      GmshElementBlock& block = file.blocks[b];
      char* name = nullptr;
      int order = 0, primary = 0;
      Owned<double> local{g};
      g.element_properties(block.type, &name, &block.dim, &order, &block.nodes_per_element, &local.p, &local.n, &primary, &ierr);
      block.name = take_string(g, name);
      block.nodes.reserve(node_tags[b].size());
      for (std::size_t tag : node_tags[b]) block.nodes.push_back(node_index(tag));
    }
  }
  // Physical groups: name, nodes, and the tags of their elements.
  Owned<int> groups{g};
  g.physical_groups(&groups.p, &groups.n, -1, &ierr);
  for (std::size_t k = 0; k + 1 < groups.n; k += 2) {
    GmshGroup group;
    group.dim = groups.p[k];
    group.tag = groups.p[k + 1];
    char* name = nullptr;
    g.physical_name(group.dim, group.tag, &name, &ierr);
    group.name = take_string(g, name);
    if (group.name.empty()) group.name = std::to_string(group.tag);
    {
      Owned<std::size_t> tags{g};
      Owned<double> coord{g};
      g.nodes_for_group(group.dim, group.tag, &tags.p, &tags.n, &coord.p, &coord.n, &ierr);
      for (std::size_t i = 0; i < tags.n; ++i) group.nodes.push_back(node_index(tags.p[i]));
    }
    std::vector<std::size_t> elements;
    Owned<int> entities{g};
    g.entities_for_group(group.dim, group.tag, &entities.p, &entities.n, &ierr);
    for (std::size_t e = 0; e < entities.n; ++e) {
      Owned<int> types{g};
      std::size_t **etags = nullptr, **enodes = nullptr, *etags_n = nullptr, *enodes_n = nullptr, etags_nn = 0, enodes_nn = 0;
      g.elements(&types.p, &types.n, &etags, &etags_n, &etags_nn, &enodes, &enodes_n, &enodes_nn, group.dim, entities.p[e], &ierr);
      for (std::size_t b = 0; b < etags_nn; ++b) {
        elements.insert(elements.end(), etags[b], etags[b] + etags_n[b]);
        g.free(etags[b]);
      }
      for (std::size_t b = 0; b < enodes_nn; ++b) g.free(enodes[b]);
      g.free(etags), g.free(etags_n), g.free(enodes), g.free(enodes_n);
    }
    file.groups.push_back(std::move(group));
    file.group_elements.push_back(std::move(elements));
  }
  return file;
}

std::unordered_set<std::size_t> elements_of_group(const GmshFile& file, const std::string& name, int dim, const std::string& where,
                                                  const std::string& key) {
  if (name.empty()) return {};
  for (std::size_t k = 0; k < file.groups.size(); ++k)
    if (file.groups[k].name == name && file.groups[k].dim == dim) return {file.group_elements[k].begin(), file.group_elements[k].end()};
  const char* kinds[] = {"point", "curve", "surface", "volume"};
  std::string groups;
  for (const auto& g : file.groups) groups += (groups.empty() ? "" : ", ") + ("\"" + g.name + "\" (" + kinds[std::clamp(g.dim, 0, 3)] + ")");
  throw InputError(where + ": error: " + key + ": " + file.path + ": no physical " + kinds[std::clamp(dim, 0, 3)] + " named \"" + name +
                   "\" (its physical groups: " + (groups.empty() ? "none" : groups) + ")");
}

}  // namespace loom
