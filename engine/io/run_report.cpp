#include "engine/io/run_report.hpp"

#include <cstdio>
#include <sstream>

#include "engine/core/interrupt.hpp"

namespace loom {

std::string json_escape(const std::string& s) {
  std::string r;
  for (char c : s) {
    switch (c) {
      case '"': r += "\\\""; break;
      case '\\': r += "\\\\"; break;
      case '\n': r += "\\n"; break;
      case '\t': r += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          r += buf;
        } else {
          r += c;
        }
    }
  }
  return r;
}

std::string run_json(const RunIdentity& id, const RunSummary& s) {
  std::ostringstream os;
  os.precision(12);
  os << "{\n"
     << "  \"loom_version\": \"" << json_escape(id.version) << "\",\n"
     << "  \"scene_file\": \"" << json_escape(id.scene_file) << "\",\n"
     << "  \"scene_name\": \"" << json_escape(id.scene_name) << "\",\n"
     << "  \"scene_hash\": \"" << json_escape(id.scene_hash) << "\",\n"
     << "  \"method\": \"" << json_escape(id.method) << "\",\n"
     << "  \"threads\": " << s.threads << ",\n"
     << "  \"ranks\": " << s.ranks << ",\n"
     << "  \"dofs\": " << s.dofs << ",\n"
     << "  \"cells\": " << s.cells << ",\n"
     << "  \"steps_requested\": " << s.steps_requested << ",\n"
     << "  \"steps_done\": " << s.steps_done << ",\n"
     << "  \"status\": \"" << (!s.converged ? "failed" : s.completed ? "completed" : s.stopped ? "stopped" : "interrupted") << "\",\n"
     << "  \"converged\": " << (s.converged ? "true" : "false") << ",\n"
     << "  \"completed\": " << (s.completed ? "true" : "false") << ",\n"
     << "  \"settled\": " << (s.settled ? "true" : "false") << ",\n"
     << "  \"interrupted_by\": \"" << (s.interrupted_by ? signal_name(s.interrupted_by) : "") << "\",\n"
     << "  \"restarted_from_step\": " << (s.restarted ? std::to_string(s.restarted_from) : std::string("null")) << ",\n"
     << "  \"last_converged_step\": " << s.last_converged_step << ",\n"
     << "  \"last_converged_time\": " << s.last_converged_time << ",\n"
     << "  \"newton_iterations\": " << s.newton_iterations << ",\n"
     << "  \"cutbacks\": " << s.cutbacks << ",\n"
     << "  \"linear_solver\": \"" << json_escape(s.linear_solver) << "\",\n"
     << "  \"factorizations\": " << s.factorizations << ",\n"
     << "  \"reused_solves\": " << s.reused_solves << ",\n"
     << "  \"gmres_iterations\": " << s.gmres_iterations << ",\n"
     << "  \"linear_iterations\": " << s.linear_iterations << ",\n"
     << "  \"preconditioner_set_ups\": " << s.preconditioner_set_ups << ",\n"
     << "  \"wall_seconds\": " << s.wall_seconds << ",\n"
     << "  \"failure\": \"" << json_escape(s.failure) << "\"\n"
     << "}\n";
  return os.str();
}

}  // namespace loom
