#include "engine/timing/profile.hpp"

#include <algorithm>
#include <functional>
#include <iomanip>
#include <map>
#include <memory>
#include <sstream>

namespace loom {
namespace {

struct Node {
  std::string name;
  long long calls = 0;
  double start = 0.0, end = 0.0, seconds = 0.0;
  bool synthetic = false;   // a level no scope timed ("iteration k", or a parent that did not run)
  bool concurrent = false;  // ran beside its step's systems, not inside its parent
  std::vector<std::unique_ptr<Node>> children;

  // The child on the path `label` (a concurrent entry is off every path).
  Node* child(const std::string& label) {
    for (auto& c : children)
      if (c->name == label && !c->concurrent) return c.get();
    return nullptr;
  }
  Node* concurrent_child(const std::string& name) {
    for (auto& c : children)
      if (c->name == name && c->concurrent) return c.get();
    children.push_back(std::make_unique<Node>());
    children.back()->name = name;
    children.back()->concurrent = true;
    return children.back().get();
  }
  Node* add_child(const std::string& label) {
    children.push_back(std::make_unique<Node>());
    children.back()->name = label;
    return children.back().get();
  }
};

std::vector<std::string> split(const std::string& name) {
  std::vector<std::string> parts;
  std::size_t begin = 0;
  for (;;) {
    const std::size_t slash = name.find('/', begin);
    parts.push_back(name.substr(begin, slash == std::string::npos ? std::string::npos : slash - begin));
    if (slash == std::string::npos) return parts;
    begin = slash + 1;
  }
}

void merge(Node& n, const ProfileEvent& e) {
  if (n.calls == 0 && !n.synthetic) n.start = e.start, n.end = e.start;
  n.synthetic = false;
  ++n.calls;
  n.seconds += e.seconds;
  n.start = std::min(n.start, e.start);
  n.end = std::max(n.end, e.start + e.seconds);
}

// Inserts an event below `root` (a step); events must come in order of start time so that a parent scope
// is in the tree before its children. `bounded`: root.start and root.end are the graph run's; a scope outside
// them (one timed between two runs, such as a checkpoint) is concurrent too.
void insert(Node& root, const ProfileEvent& e, bool bounded) {
  std::vector<std::string> path = split(e.name);
  if (e.iteration >= 0 && path.size() >= 2 && path[0] == kNewtonScope) path.insert(path.begin() + 1, "iteration " + std::to_string(e.iteration));
  const double end = e.start + e.seconds;
  const double slack = 1e-7;  // clock granularity
  Node* at = &root;
  for (std::size_t k = 0; k + 1 < path.size(); ++k) {
    Node* next = at->child(path[k]);
    const bool iteration_level = k == 1 && e.iteration >= 0 && path[0] == kNewtonScope;
    if (!next) {
      if (!iteration_level && k == 0) {
        // The parent system did not run in this step (yet): the scope ran on its own (the writer).
        merge(*root.concurrent_child(e.name), e);
        return;
      }
      next = at->add_child(path[k]);
      next->synthetic = true;
      next->start = e.start, next->end = end;
    } else if (!next->synthetic && (e.start < next->start - slack || end > next->end + slack)) {
      merge(*root.concurrent_child(e.name), e);
      return;
    }
    if (next->synthetic) next->start = std::min(next->start, e.start), next->end = std::max(next->end, end);
    at = next;
  }
  if (at == &root && bounded && (e.start < root.start - slack || end > root.end + slack)) {
    merge(*root.concurrent_child(e.name), e);
    return;
  }
  Node* leaf = at->child(path.back());
  if (!leaf) leaf = at->add_child(path.back());
  merge(*leaf, e);
}

// A synthetic level spans its children: from the first one's start to the last one's end, the untimed work
// between them included (an iteration's convergence test and line-search logic, or the time its thread was
// descheduled between two phases on a loaded machine). The sum of its children would be shorter than that
// span by those gaps, and the last phases would end after their parent.
void settle(Node& n) {
  for (auto& c : n.children) settle(*c);
  if (n.synthetic) n.seconds = n.end - n.start;
}

void write_node(std::ostream& os, const Node& n, const std::string& indent) {
  os << indent << "{\"name\": \"" << n.name << "\", \"calls\": " << n.calls << ", \"start\": " << n.start
     << ", \"seconds\": " << n.seconds;
  if (n.concurrent) os << ", \"concurrent\": true";
  if (!n.children.empty()) {
    os << ", \"children\": [\n";
    for (std::size_t k = 0; k < n.children.size(); ++k) {
      write_node(os, *n.children[k], indent + "  ");
      os << (k + 1 < n.children.size() ? ",\n" : "\n");
    }
    os << indent << "]";
  }
  os << "}";
}

}  // namespace

void write_profile_json(std::ostream& os, const std::vector<ProfileRun>& runs, const std::vector<ProfileEvent>& events,
                        const std::string& indent) {
  std::vector<const ProfileEvent*> sorted;
  for (const auto& e : events) sorted.push_back(&e);
  // By start. Of scopes with the same clock reading at their start (some virtual machines' clocks step by
  // 100 ns), a parent before its child (the shorter name), and phases one after the other in the order they
  // ran, as recorded (when they ended): the longer one first would put a quick update after the assembly
  // that followed it.
  auto depth = [](const ProfileEvent* e) { return std::count(e->name.begin(), e->name.end(), '/'); };
  std::stable_sort(sorted.begin(), sorted.end(), [&](const ProfileEvent* a, const ProfileEvent* b) {
    return a->start != b->start ? a->start < b->start : depth(a) < depth(b);
  });
  // Run -1 (the initial state, before the first graph run) becomes "step 0".
  std::vector<Node> steps(runs.size() + 1);
  steps[0].name = "step 0";
  for (std::size_t r = 0; r < runs.size(); ++r) {
    steps[r + 1].name = "step " + std::to_string(runs[r].step);
    steps[r + 1].start = runs[r].start, steps[r + 1].end = runs[r].start + runs[r].seconds;
  }
  // A run's events lie within its time, once it ended (seconds > 0).
  for (const ProfileEvent* e : sorted)
    if (e->run >= -1 && e->run < int(runs.size()))
      insert(steps[std::size_t(e->run + 1)], *e, e->run >= 0 && runs[std::size_t(e->run)].seconds > 0.0);

  const auto flags = os.flags();
  os << std::setprecision(9) << "{\n" << indent << "  \"steps\": [";
  bool first = true;
  for (std::size_t k = 0; k < steps.size(); ++k) {
    Node& s = steps[k];
    for (auto& c : s.children) settle(*c);
    if (k == 0 && s.children.empty()) continue;
    double start = 0.0, seconds = 0.0, t = 0.0, dt = 0.0;
    int step = 0;
    if (k > 0) {
      const ProfileRun& r = runs[k - 1];
      step = r.step, t = r.t, dt = r.dt, start = r.start, seconds = r.seconds;
    } else {
      start = s.children.front()->start;
      for (const auto& c : s.children) seconds = std::max(seconds, c->end - start);
    }
    os << (first ? "\n" : ",\n") << indent << "    {\"name\": \"" << s.name << "\", \"step\": " << step << ", \"t\": " << t
       << ", \"dt\": " << dt << ", \"start\": " << start << ", \"seconds\": " << seconds << ", \"children\": [";
    for (std::size_t c = 0; c < s.children.size(); ++c) {
      os << (c ? ",\n" : "\n");
      write_node(os, *s.children[c], indent + "      ");
    }
    os << (s.children.empty() ? "]}" : "\n" + indent + "    ]}");
    first = false;
  }
  os << "\n" << indent << "  ]\n" << indent << "}";
  os.flags(flags);
}

std::vector<std::pair<std::string, double>> most_expensive(const std::vector<TimerTotal>& timers, std::size_t n) {
  std::map<std::string, double> self;
  for (const auto& t : timers) self[t.name] += t.total;
  for (const auto& t : timers) {
    const auto slash = t.name.rfind('/');
    if (slash == std::string::npos) continue;
    auto parent = self.find(t.name.substr(0, slash));
    if (parent != self.end()) parent->second -= t.total;
  }
  std::vector<std::pair<std::string, double>> r;
  for (const auto& [name, s] : self) r.emplace_back(name, std::max(0.0, s));
  std::stable_sort(r.begin(), r.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
  if (r.size() > n) r.resize(n);
  return r;
}

}  // namespace loom
