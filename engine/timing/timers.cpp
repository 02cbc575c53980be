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
  runs_.clear();
  events_.clear();
}

void Timers::enable_profile() {
  std::lock_guard lock(mutex_);
  profiling_ = true;
  origin_ = Clock::now();
}

void Timers::add_scope(const std::string& name, const ProfileMark& mark, Clock::time_point start, Clock::time_point end) {
  const double seconds = std::chrono::duration<double>(end - start).count();
  std::lock_guard lock(mutex_);
  auto& s = stats_[name];
  ++s.calls;
  s.total += seconds;
  s.max = std::max(s.max, seconds);
  if (!profiling_) return;
  events_.push_back({name, mark.run, mark.iteration, std::chrono::duration<double>(start - origin_).count(), seconds});
}

void Timers::begin_graph_run(int step, double t, double dt) {
  if (!profiling_) return;
  std::lock_guard lock(mutex_);
  runs_.push_back({step, t, dt, std::chrono::duration<double>(Clock::now() - origin_).count(), 0.0});
  run_.store(int(runs_.size()) - 1, std::memory_order_relaxed);
}

void Timers::end_graph_run() {
  if (!profiling_) return;
  std::lock_guard lock(mutex_);
  if (runs_.empty()) return;
  runs_.back().seconds = std::chrono::duration<double>(Clock::now() - origin_).count() - runs_.back().start;
}

std::vector<ProfileRun> Timers::profile_runs() const {
  std::lock_guard lock(mutex_);
  return runs_;
}

std::vector<ProfileEvent> Timers::profile_events() const {
  std::lock_guard lock(mutex_);
  return events_;
}

namespace {

std::vector<std::pair<std::string, double>> top_three(const std::map<std::string, TimerStats>& stats) {
  std::vector<TimerTotal> totals;
  for (const auto& [name, s] : stats) totals.push_back({name, s.total});
  return most_expensive(totals, 3);
}

}  // namespace

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
  const auto precision = os.precision();  // the caller's, restored at the end
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
  os << "most expensive (self time):";
  int rank = 0;
  for (const auto& [name, self] : top_three(stats)) {
    os << (rank ? "," : "") << " ";
    os << ++rank << ". " << name << " " << std::fixed << std::setprecision(3) << self << " s ("
       << std::setprecision(1) << (wall > 0 ? 100.0 * self / wall : 0.0) << "%)";
  }
  os << "\n";
  os.flags(flags);
  os.precision(precision);
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
  os << "\n  },\n  \"most_expensive\": [";
  first = true;
  for (const auto& [name, self] : top_three(stats)) {
    os << (first ? "" : ", ") << "{\"name\": \"" << name << "\", \"self\": " << self << ", \"share\": " << (wall > 0 ? self / wall : 0.0) << "}";
    first = false;
  }
  os << "]";
  if (profiling_) {
    os << ",\n  \"profile\": ";
    write_profile_json(os, profile_runs(), profile_events(), "  ");
  }
  os << "\n}\n";
  os.flags(flags);
}

}  // namespace loom
