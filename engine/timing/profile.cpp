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

  Node* child(const std::string& label) {
    for (auto& c : children)
      if (c->name == label) return c.get();
    return nullptr;
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
// is in the tree before its children.
void insert(Node& root, const ProfileEvent& e) {
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
        // The parent system did not run in this step: the scope ran on its own (the writer).
        Node* n = root.child(e.name);
        if (!n) n = root.add_child(e.name), n->concurrent = true;
        merge(*n, e);
        return;
      }
      next = at->add_child(path[k]);
      next->synthetic = true;
      next->start = e.start, next->end = end;
    } else if (!next->synthetic && (e.start < next->start - slack || end > next->end + slack)) {
      Node* n = root.child(e.name);
      if (!n) n = root.add_child(e.name), n->concurrent = true;
      merge(*n, e);
      return;
    }
    if (next->synthetic) next->start = std::min(next->start, e.start), next->end = std::max(next->end, end);
    at = next;
  }
  Node* leaf = at->child(path.back());
  if (!leaf) leaf = at->add_child(path.back());
  merge(*leaf, e);
}

// A synthetic level lasts as long as its children together.
double settle(Node& n) {
  double sum = 0.0;
  for (auto& c : n.children) {
    const double s = settle(*c);
    if (!c->concurrent) sum += s;
  }
  if (n.synthetic) n.seconds = sum;
  return n.seconds;
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
  // By start; a scope that starts with its child (same clock reading) first: the longer one.
  std::stable_sort(sorted.begin(), sorted.end(), [](const ProfileEvent* a, const ProfileEvent* b) {
    return a->start != b->start ? a->start < b->start : a->seconds > b->seconds;
  });
  // Run -1 (the initial state, before the first graph run) becomes "step 0".
  std::vector<Node> steps(runs.size() + 1);
  steps[0].name = "step 0";
  for (std::size_t r = 0; r < runs.size(); ++r) steps[r + 1].name = "step " + std::to_string(runs[r].step);
  for (const ProfileEvent* e : sorted)
    if (e->run >= -1 && e->run < int(runs.size())) insert(steps[std::size_t(e->run + 1)], *e);

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
