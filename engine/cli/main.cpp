// The loom program: run, check, info and schema (DESIGN §5). Exit codes: 0 success, 1 the run failed,
// 2 bad input (scene or command line).
#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/info.h>

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "engine/cli/mpi_launch.hpp"
#include "engine/core/errors.hpp"
#include "engine/core/interrupt.hpp"
#include "engine/io/console_format.hpp"
#include "engine/io/files.hpp"
#include "engine/io/run_files.hpp"
#include "engine/io/run_report.hpp"
#include "engine/methods/method.hpp"
#include "engine/scene/scene_loader.hpp"
#include "engine/scene/schema.hpp"

namespace {

constexpr const char* kUsage =
    "usage:\n"
    "  loom run SCENE [--out DIR] [--threads N] [--set key.path=value]... [--quiet] [--verbose] [--profile]\n"
    "               [--restart DIR|FILE] [--stop-after N]\n"
    "  loom check SCENE [--set key.path=value]...   validate the scene and build its mesh, do not run\n"
    "  loom info SCENE [--set key.path=value]...    print the step graph and the store sizes\n"
    "  loom schema [--markdown]                      print every scene key with type, default and meaning\n"
    "  loom --version\n"
    "--set addresses arrays of tables by index or by name: body[0].mesh.divisions=[16,16],\n"
    "material[rubber].nu=0.3. --profile adds per-step, per-system and per-Newton-iteration timings to\n"
    "timings.json. --restart continues the run whose checkpoint is in DIR (the newest) or FILE, in that\n"
    "directory; --stop-after N stops after step N and writes its checkpoint. SIGINT / SIGTERM stop after the\n"
    "current step. Exit codes: 0 success, 1 the run failed, 2 bad input, 128 + signal when interrupted.\n";

struct Args {
  std::string program, command, scene, out, restart;
  std::vector<std::string> sets;
  int threads = 0, stop_after = 0;
  bool quiet = false, markdown = false, verbose = false, profile = false;
};

Args parse(int argc, char** argv) {
  Args a;
  std::vector<std::string> v(argv + 1, argv + argc);
  a.program = argc > 0 ? argv[0] : "loom";
  LOOM_CHECK(!v.empty(), loom::InputError, "missing command\n" << kUsage);
  a.command = v[0];
  for (std::size_t i = 1; i < v.size(); ++i) {
    const std::string& s = v[i];
    auto value = [&](const char* opt) {
      LOOM_CHECK(i + 1 < v.size(), loom::InputError, opt << " needs a value\n" << kUsage);
      return v[++i];
    };
    auto positive = [&](const char* opt) {
      const std::string n = value(opt);
      try {
        std::size_t used = 0;
        const int count = std::stoi(n, &used);
        LOOM_CHECK(used == n.size() && count >= 1, loom::InputError, "");
        return count;
      } catch (const std::exception&) {
        throw loom::InputError(std::string(opt) + " needs a positive integer, got '" + n + "'");
      }
    };
    if (s == "--out") a.out = value("--out");
    else if (s == "--restart") a.restart = value("--restart");
    else if (s == "--stop-after") a.stop_after = positive("--stop-after");
    else if (s == "--set") a.sets.push_back(value("--set"));
    else if (s.rfind("--set=", 0) == 0) a.sets.push_back(s.substr(6));
    else if (s == "--threads") a.threads = positive("--threads");
    else if (s == "--quiet") a.quiet = true;
    else if (s == "--verbose") a.verbose = true;
    else if (s == "--profile") a.profile = true;
    else if (s == "--markdown") a.markdown = true;
    else if (!s.empty() && s[0] == '-') throw loom::InputError("unknown option " + s + "\n" + kUsage);
    else if (a.scene.empty()) a.scene = s;
    else throw loom::InputError("unexpected argument " + s + "\n" + kUsage);
  }
  return a;
}

void print_warnings(const loom::SceneSpec& scene) {
  for (const auto& w : scene.warnings) std::cerr << w << "\n";
}

// Where the output goes: --out, the scene's output.directory, or the directory of the checkpoint a restart
// continues (a restarted run appends to that run's files).
void resolve_output(const Args& a, const loom::SceneSpec& scene, loom::RunOptions& options) {
  options.output_directory = a.out.empty() ? scene.output.directory : a.out;
  std::ostringstream origin;
  if (!a.out.empty()) origin << "--out " << a.out;
  else origin << scene.output.where << ": output.directory";
  options.output_origin = origin.str();
  if (a.restart.empty()) return;
  options.restart_file = loom::find_checkpoint(a.restart);
  const std::string dir = std::filesystem::path(options.restart_file).parent_path().string();
  std::error_code ec;
  LOOM_CHECK(a.out.empty() || std::filesystem::equivalent(a.out, dir.empty() ? "." : dir, ec), loom::InputError,
             "--out " << a.out << ": error: a restarted run continues in the directory of its checkpoint (" << dir
                      << "); leave --out out");
  options.output_directory = dir.empty() ? "." : dir;
  options.output_origin = "--restart " + a.restart;
}

void print_probes(const loom::SceneSpec& scene, const loom::RunSummary& summary, const std::vector<double>& values) {
  if (scene.probes.empty() || values.size() != scene.probes.size()) return;
  std::size_t width = 0;
  for (const auto& p : scene.probes) width = std::max(width, p.name.size());
  std::cout << "probes at step " << summary.last_converged_step << " (t = "
            << summary.last_step_time << "):\n";
  for (std::size_t k = 0; k < values.size(); ++k) {
    char value[32];
    std::snprintf(value, sizeof value, "%.6g", values[k]);
    std::cout << "  " << scene.probes[k].name << std::string(width - scene.probes[k].name.size() + 2, ' ') << value;
    if (const auto& p = scene.probes[k]; p.has_reference) {  // e.g. "(reference 7.771: -0.63 %)"
      char against[96];
      if (p.reference != 0.0) std::snprintf(against, sizeof against, "   (reference %.6g: %+.2f %%)", p.reference, 100.0 * (values[k] / p.reference - 1.0));
      else std::snprintf(against, sizeof against, "   (reference 0: %+.3g)", values[k]);
      std::cout << against;
    }
    std::cout << "\n";
  }
}

// Under `mpirun -n N` every rank runs; rank 0 alone prints and writes (engine/cli/mpi_launch.hpp).
int run(const Args& a, const loom::MpiLaunch& launch) {
  std::optional<oneapi::tbb::global_control> limit;
  // Ranks share the cores: one thread each unless --threads says otherwise.
  const int wanted = a.threads > 0 ? a.threads : launch.size > 1 ? 1 : 0;
  if (wanted > 0) limit.emplace(oneapi::tbb::global_control::max_allowed_parallelism, std::size_t(wanted));
  const int threads = int(oneapi::tbb::global_control::active_value(oneapi::tbb::global_control::max_allowed_parallelism));

  const loom::SceneSpec scene = loom::load_scene(a.scene, a.sets);
  loom::join_ranks(launch, scene);
  const bool lead = launch.lead();
  if (lead) print_warnings(scene);
  loom::RunOptions options;
  resolve_output(a, scene, options);
  options.threads = threads;
  options.write_files = lead;
  options.progress = !a.quiet && lead;
  options.quiet = a.quiet || !lead;
  options.log = lead ? &std::cerr : nullptr;
  options.verbose = a.verbose && lead;
  options.profile = a.profile;
  options.stop_after = a.stop_after;
  loom::install_interrupt_handlers();
  auto method = loom::make_method_run(scene, options);
  loom::RunSummary summary = method->run();
  summary.threads = threads;
  summary.ranks = launch.size;
  if (!lead) return !summary.converged ? 1 : summary.interrupted_by && !summary.stopped ? 128 + summary.interrupted_by : 0;

  const loom::RunIdentity id{LOOM_VERSION, a.scene, scene.scene.name, scene.text_hash, loom::method_name(scene.scene.method)};
  loom::write_file_atomic(options.output_directory + "/run.json", loom::run_json(id, summary));
  {
    std::ostringstream json;
    method->timers().write_json(json, summary.wall_seconds);
    loom::write_file_atomic(options.output_directory + "/timings.json", json.str());
    if (!a.quiet) {
      print_probes(scene, summary, method->probe_values());
      method->timers().print_table(std::cout, summary.wall_seconds);
    }
  }
  const std::string steps = loom::count_of(summary.steps_done, "step");
  if (!summary.converged) {
    // The last converged state may lie inside the failed step (converged sub-steps before a cut-back gave up).
    const double step_end = summary.last_step_time;
    std::cerr << "loom: the run failed: " << summary.failure << "\n"
              << "loom: last converged step " << summary.last_converged_step << " (t = " << step_end << ")";
    if (summary.last_converged_time > step_end * (1 + 1e-12) + 1e-300)
      std::cerr << "; sub-steps of the failed step converged up to t = " << summary.last_converged_time;
    if (summary.cutbacks > 0) std::cerr << "; " << loom::count_of(summary.cutbacks, "cut-back") << " in the run";
    std::cerr << "; the output written so far is in " << options.output_directory << "\n";
    return 1;
  }
  if (summary.interrupted_by || summary.stopped) {
    // A run that stops early always writes the checkpoint of its last step (and that step as a frame).
    std::cerr << "loom: " << (summary.stopped ? "stopped as asked" : std::string("interrupted by ") + loom::signal_name(summary.interrupted_by))
              << " after step " << summary.last_converged_step << " of " << scene.time.steps << " (t = " << summary.last_converged_time
              << "); output in " << options.output_directory << "; continue with: " << a.program << " run " << a.scene;
    for (const auto& set : a.sets) std::cerr << " --set '" << set << "'";
    std::cerr << " --restart " << options.output_directory << "\n";
    return summary.stopped ? 0 : 128 + summary.interrupted_by;
  }
  if (!a.quiet && summary.settled) {
    const loom::ProbeSpec& watched = scene.probes[std::size_t(scene.time.stop_probe)];
    std::cout << "loom: settled at step " << summary.last_converged_step << " of " << scene.time.steps << " (t = " << summary.last_converged_time
              << "): " << (scene.time.stop_rate ? "the rate of change of " + watched.name : "|" + watched.name + "|") << " < "
              << scene.time.stop_below << " (time.stop_when)\n";
  }
  if (!a.quiet)
    std::cout << "loom: " << steps << (summary.restarted ? " (continued from step " + std::to_string(summary.restarted_from) + ")" : "")
              << ", " << loom::count_of(summary.newton_iterations, "Newton iteration")
              << (summary.cutbacks > 0 ? ", " + loom::count_of(summary.cutbacks, "cut-back") : std::string()) << ", "
              << loom::format_seconds(summary.wall_seconds)
              << " wall; output in " << options.output_directory << "\n";
  return 0;
}

}  // namespace

// Debian's CHOLMOD runs its supernodal factorization in OpenMP teams of a fixed size (4) whatever the
// machine, and OpenBLAS spins idle threads: on two cores both oversubscribe the oneTBB workers and make a
// factorization 1.6-2.9x slower (perf/README.md). The OpenMP runtime reads its limit when it is loaded,
// before main, so loom sets OMP_THREAD_LIMIT=1 and OPENBLAS_NUM_THREADS=1 (unless the user set them) and
// starts itself again, once.
void pin_solver_threads(char** argv) {
  if (std::getenv("OMP_THREAD_LIMIT") || std::getenv("LOOM_NO_REEXEC")) return;
  setenv("OMP_THREAD_LIMIT", "1", 1);
  if (!std::getenv("OPENBLAS_NUM_THREADS")) setenv("OPENBLAS_NUM_THREADS", "1", 1);
  setenv("LOOM_NO_REEXEC", "1", 1);
  execv("/proc/self/exe", argv);  // returns only on failure: then go on as we are
}

int main(int argc, char** argv) {
  if (argc > 1 && std::string(argv[1]) == "run") pin_solver_threads(argv);
  const loom::MpiLaunch launch = loom::mpi_launch();
  // Ranks other than 0 say nothing: every rank meets the same errors, and rank 0 reports them.
  if (!launch.lead()) std::cout.setstate(std::ios::failbit), std::cerr.setstate(std::ios::failbit);
  try {
    const Args a = parse(argc, argv);
    if (a.command == "--version" || a.command == "version") {
      std::cout << "loom " << LOOM_VERSION << "\n";
      return 0;
    }
    if (a.command == "--help" || a.command == "help" || a.command == "-h") {
      std::cout << kUsage;
      return 0;
    }
    if (a.command == "schema") {
      loom::print_schema(std::cout, a.markdown);
      return 0;
    }
    LOOM_CHECK(a.command == "run" || a.command == "check" || a.command == "info", loom::InputError,
               "unknown command '" << a.command << "'\n" << kUsage);
    LOOM_CHECK(!a.scene.empty(), loom::InputError, "missing SCENE\n" << kUsage);
    if (a.command == "run") return run(a, launch);
    LOOM_CHECK(a.restart.empty() && a.stop_after == 0, loom::InputError, "--restart and --stop-after are options of loom run\n" << kUsage);
    const loom::SceneSpec scene = loom::load_scene(a.scene, a.sets);
    print_warnings(scene);
    loom::RunOptions options;
    options.write_files = false;
    options.progress = false;
    auto method = loom::make_method_run(scene, options);
    if (a.command == "info") method->describe(std::cout);
    else std::cout << a.scene << ": ok\n";
    return 0;
  } catch (const loom::InputError& e) {
    std::cerr << e.what();
    if (std::string(e.what()).back() != '\n') std::cerr << "\n";
    return 2;
  } catch (const loom::RunError& e) {
    std::cerr << "loom: the run failed: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "loom: internal error: " << e.what() << "\n";
    return 1;
  }
}
