#include "engine/graph/step_graph.hpp"

#include <oneapi/tbb/flow_graph.h>
#include <oneapi/tbb/profiling.h>

#include <algorithm>
#include <exception>
#include <mutex>

#include "engine/core/errors.hpp"

namespace loom {

namespace flow = oneapi::tbb::flow;

struct StepGraph::Impl {
  struct Node {
    std::string name, detail;
    Access access;
    std::function<void()> body;
    std::function<bool()> predicate;
    std::vector<std::size_t> preds;  // all derived predecessors
    std::vector<std::size_t> direct;  // transitive reduction
    std::unique_ptr<flow::continue_node<flow::continue_msg>> tbb_node;
  };

  explicit Impl(Timers& t) : timers(t) {}

  Timers& timers;
  flow::graph graph;
  flow::broadcast_node<flow::continue_msg> start{graph};
  std::vector<Node> nodes;
  std::unordered_map<const void*, std::string> store_names;
  bool built = false;

  std::mutex error_mutex;
  std::exception_ptr error;
  std::string error_node;

  std::string store_name(const void* p) const {
    auto it = store_names.find(p);
    return it == store_names.end() ? "(unnamed)" : it->second;
  }
};

namespace {
bool intersects(const std::vector<const void*>& a, const std::vector<const void*>& b) {
  for (const void* x : a)
    if (std::find(b.begin(), b.end(), x) != b.end()) return true;
  return false;
}
}  // namespace

StepGraph::StepGraph(std::string name, const StepContext& ctx, Timers& timers)
    : impl_(std::make_unique<Impl>(timers)), name_(std::move(name)), ctx_(ctx) {}

StepGraph::~StepGraph() {
  if (impl_) impl_->graph.wait_for_all();
}

void StepGraph::name_store(const void* store, std::string name) { impl_->store_names[store] = std::move(name); }

std::size_t StepGraph::add_node(std::string name, Access access, std::function<void()> body, std::string detail) {
  LOOM_ASSERT(!impl_->built, "nodes must be added before build()");
  Impl::Node n;
  n.name = std::move(name);
  n.detail = std::move(detail);
  n.access = std::move(access);
  n.body = std::move(body);
  impl_->nodes.push_back(std::move(n));
  return impl_->nodes.size() - 1;
}

void StepGraph::run_if(std::size_t node, const void* reads, std::function<bool()> predicate) {
  LOOM_ASSERT(!impl_->built, "run_if must be set before build()");
  auto& n = impl_->nodes.at(node);
  n.predicate = std::move(predicate);
  if (reads) n.access.reads.push_back(reads);
}

std::size_t StepGraph::size() const { return impl_->nodes.size(); }

void StepGraph::build() {
  auto& nodes = impl_->nodes;
  const std::size_t n = nodes.size();
  // Data hazards between earlier node i and later node j: write-read, write-write, read-write.
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < j; ++i) {
      const auto& a = nodes[i].access;
      const auto& b = nodes[j].access;
      if (intersects(a.writes, b.reads) || intersects(a.writes, b.writes) || intersects(a.reads, b.writes))
        nodes[j].preds.push_back(i);
    }
  // Transitive reduction: drop i -> j when i reaches j through another predecessor of j.
  std::vector<std::vector<char>> reach(n, std::vector<char>(n, 0));
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i : nodes[j].preds) {
      reach[i][j] = 1;
      for (std::size_t k = 0; k < n; ++k)
        if (reach[k][i]) reach[k][j] = 1;
    }
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i : nodes[j].preds) {
      bool implied = false;
      for (std::size_t k : nodes[j].preds)
        if (k != i && reach[i][k]) implied = true;
      if (!implied) nodes[j].direct.push_back(i);
    }

  Impl* impl = impl_.get();
  for (std::size_t j = 0; j < n; ++j) {
    auto* node = &nodes[j];
    node->tbb_node = std::make_unique<flow::continue_node<flow::continue_msg>>(
        impl->graph, [impl, node](const flow::continue_msg&) {
          {
            std::lock_guard lock(impl->error_mutex);
            if (impl->error) return flow::continue_msg();
          }
          if (node->predicate && !node->predicate()) return flow::continue_msg();
          try {
            ScopedTimer timer(impl->timers, node->name);
            node->body();
          } catch (...) {
            std::lock_guard lock(impl->error_mutex);
            if (!impl->error) impl->error = std::current_exception(), impl->error_node = node->name;
          }
          return flow::continue_msg();
        });
    oneapi::tbb::profiling::set_name(*node->tbb_node, node->name.c_str());
  }
  for (std::size_t j = 0; j < n; ++j) {
    if (nodes[j].direct.empty()) flow::make_edge(impl->start, *nodes[j].tbb_node);
    for (std::size_t i : nodes[j].direct) flow::make_edge(*nodes[i].tbb_node, *nodes[j].tbb_node);
  }
  impl->built = true;
}

void StepGraph::run() {
  LOOM_ASSERT(impl_->built, "build() the graph before running it");
  impl_->error = nullptr;
  impl_->timers.begin_graph_run(ctx_.step, ctx_.t, ctx_.dt);
  impl_->start.try_put(flow::continue_msg());
  impl_->graph.wait_for_all();
  impl_->timers.end_graph_run();
  if (!impl_->error) return;
  const std::string where = impl_->error_node;
  try {
    std::rethrow_exception(impl_->error);
  } catch (const InputError& e) {
    throw InputError(std::string(e.what()));
  } catch (const RunError& e) {
    throw RunError("in system " + where + ": " + e.what());
  } catch (const std::exception& e) {
    throw RunError("in system " + where + ": " + e.what());
  }
}

std::vector<std::pair<std::string, std::string>> StepGraph::edges() const {
  std::vector<std::pair<std::string, std::string>> r;
  for (const auto& node : impl_->nodes)
    for (std::size_t i : node.direct) r.emplace_back(impl_->nodes[i].name, node.name);
  return r;
}

void StepGraph::print(std::ostream& os) const {
  os << "step graph '" << name_ << "': " << impl_->nodes.size() << " nodes\n";
  for (const auto& node : impl_->nodes) {
    os << "  " << node.name;
    if (!node.detail.empty()) os << "  [" << node.detail << "]";
    os << "\n    reads:";
    for (const void* p : node.access.reads) os << " " << impl_->store_name(p);
    os << "\n    writes:";
    for (const void* p : node.access.writes) os << " " << impl_->store_name(p);
    os << "\n    after:";
    if (node.direct.empty()) os << " (start)";
    for (std::size_t i : node.direct) os << " " << impl_->nodes[i].name;
    os << "\n";
  }
}

}  // namespace loom
