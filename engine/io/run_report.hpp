// run.json: the record of a run (DESIGN §6): version, scene and its hash, threads, steps, status
// (completed, failed, interrupted by a signal, stopped at --stop-after), convergence, last converged step,
// the checkpoint step a restarted run continued from, Newton iterations, wall time.
#pragma once

#include <string>

#include "engine/drivers/run_summary.hpp"

namespace loom {

struct RunIdentity {
  std::string version, scene_file, scene_name, scene_hash, method;
};

std::string run_json(const RunIdentity& id, const RunSummary& s);
std::string json_escape(const std::string& s);

}  // namespace loom
