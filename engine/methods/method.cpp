#include "engine/methods/method.hpp"

#include "engine/core/errors.hpp"
#include "engine/methods/recipes/fem_method.hpp"
#include "engine/methods/recipes/mpm_method.hpp"

namespace loom {

std::unique_ptr<MethodRun> make_method_run(const SceneSpec& scene, const RunOptions& options) {
  switch (scene.scene.method) {
    case Method::fem:
    case Method::pfem:
    case Method::es_pfem:
      if (scene.scene.dimension == 3) return std::make_unique<FemRunT<3>>(scene, options);
      return std::make_unique<FemRun>(scene, options);
    case Method::mpm:
      if (scene.scene.dimension == 3) return std::make_unique<MpmRunT<3>>(scene, options);
      return std::make_unique<MpmRun>(scene, options);
    case Method::mpm_fem: return std::make_unique<MpmRun>(scene, options);
    default: break;
  }
  throw InputError(scene.file + ": error: scene.method: this method is not implemented yet (available: fem, pfem, es_pfem, mpm)");
}

}  // namespace loom
