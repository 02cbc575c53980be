#include "engine/timing/timers.hpp"

#include <algorithm>
#include <functional>
#include <iomanip>
#include <vector>

namespace loom {

void Timers::add(const std::string& name, double seconds) {
  std::lock_guard lock(mutex_);
  auto& s = stats_[name];
  ++s.calls;
  s.total += seconds;
  s.max = std::max(s.max, seconds);
}

std::map<std::string, TimerStats> Timers::snapshot() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

void Timers::clear() {
  std::lock_guard lock(mutex_);
  stats_.clear();
}

void Timers::print_table(std::ostream& os, double wall) const {
  const auto stats = snapshot();
  auto parent_of = [](const std::string& name) {
    const auto slash = name.rfind('/');
    return slash == std::string::npos ? std::string() : name.substr(0, slash);
  };
  // Roots by total time, each followed by its children (by total time, recursively). A root is an entry
  // whose parent is not timed itself ("writer/flush" without "writer"): it is shown under its full name,
  // so that no timer is left out of the table.
  auto by_total = [](const auto& a, const auto& b) { return a.second.total > b.second.total; };
  auto children_of = [&](const std::string& parent) {
    std::vector<std::pair<std::string, TimerStats>> r;
    for (const auto& e : stats)
      if (parent.empty() ? !stats.count(parent_of(e.first)) : parent_of(e.first) == parent) r.push_back(e);
    std::sort(r.begin(), r.end(), by_total);
    return r;
  };
  const auto flags = os.flags();
  os << std::left << std::setw(34) << "system" << std::right << std::setw(9) << "calls" << std::setw(12) << "total s"
     << std::setw(12) << "mean ms" << std::setw(12) << "max ms" << std::setw(9) << "share" << "\n";
  auto row = [&](const std::string& label, const TimerStats& s) {
    os << std::left << std::setw(34) << label << std::right << std::setw(9) << s.calls << std::fixed << std::setprecision(3)
       << std::setw(12) << s.total << std::setw(12) << 1e3 * s.total / double(std::max(1LL, s.calls)) << std::setw(12)
       << 1e3 * s.max << std::setw(8) << std::setprecision(1) << (wall > 0 ? 100.0 * s.total / wall : 0.0) << "%\n";
    os.unsetf(std::ios::fixed);
  };
  std::function<void(const std::string&, const TimerStats&, const std::string&)> print = [&](const std::string& name,
                                                                                          const TimerStats& s,
                                                                                          const std::string& indent) {
    const std::string parent = parent_of(name);
    row(indent + (indent.empty() ? name : name.substr(parent.size() + 1)), s);
    for (const auto& [child, cs] : children_of(name)) print(child, cs, indent + "  ");
  };
  for (const auto& [name, s] : children_of("")) print(name, s, "");
  os.flags(flags);
}

void Timers::write_json(std::ostream& os, double wall) const {
  const auto stats = snapshot();
  const auto flags = os.flags();
  os << std::setprecision(9) << "{\n  \"wall\": " << wall << ",\n  \"timers\": {";
  bool first = true;
  for (const auto& [name, s] : stats) {
    os << (first ? "\n" : ",\n") << "    \"" << name << "\": {\"calls\": " << s.calls << ", \"total\": " << s.total
       << ", \"mean\": " << s.total / double(std::max(1LL, s.calls)) << ", \"max\": " << s.max
       << ", \"share\": " << (wall > 0 ? s.total / wall : 0.0) << "}";
    first = false;
  }
  os << "\n  }\n}\n";
  os.flags(flags);
}

}  // namespace loom
