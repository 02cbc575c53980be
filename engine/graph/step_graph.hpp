// The step graph (DESIGN §4, STYLE §5): one oneTBB continue_node per system, created once when a recipe
// is built and run once per (sub)step. Edges are derived from what each node reads and writes, in the
// order nodes were added: a node runs after every earlier node that writes what it reads or writes, or
// reads what it writes. Systems added with add_system declare their access by their signature:
// `void f(const StepContext&, const A& in, B& out)` reads A and writes B.
#pragma once

#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <tuple>
#include <type_traits>
#include <unordered_map>
#include <vector>

#include "engine/graph/step_context.hpp"
#include "engine/timing/timers.hpp"

namespace loom {

class StepGraph {
 public:
  StepGraph(std::string name, const StepContext& ctx, Timers& timers);
  ~StepGraph();
  StepGraph(const StepGraph&) = delete;
  StepGraph& operator=(const StepGraph&) = delete;

  // Gives a store (any object passed to systems) the name shown by `loom info`.
  void name_store(const void* store, std::string name);

  struct Access {
    std::vector<const void*> reads, writes;
  };

  // Adds a node running `body`; `detail` describes inner phases (e.g. the Newton loop). Returns its index.
  std::size_t add_node(std::string name, Access access, std::function<void()> body, std::string detail = {});

  // Adds a system: access follows from the constness of fn's store parameters.
  template <class... P, class... A>
  std::size_t add_system(std::string name, void (*fn)(const StepContext&, P...), A&... stores) {
    static_assert(sizeof...(P) == sizeof...(A), "one store argument per system parameter");
    Access access;
    (classify<P>(access, &stores), ...);
    auto args = std::tuple<A&...>(stores...);
    const StepContext* ctx = &ctx_;
    return add_node(std::move(name), std::move(access), [fn, args, ctx]() { std::apply([&](auto&... s) { fn(*ctx, s...); }, args); });
  }

  // The node runs only when `predicate` holds at run time (it still completes, so successors run);
  // `reads` is the store the predicate looks at (an added read access).
  void run_if(std::size_t node, const void* reads, std::function<bool()> predicate);

  // Wires the flow graph; call once after adding every node.
  void build();
  // Runs every node once; rethrows the first exception of a node with the node's name, after the other
  // nodes have completed (nodes after a failed one are skipped).
  void run();

  void print(std::ostream& os) const;
  const std::string& name() const { return name_; }
  std::size_t size() const;
  std::vector<std::pair<std::string, std::string>> edges() const;  // reduced: no edge implied by others

 private:
  template <class P>
  static void classify(Access& access, const void* store) {
    static_assert(std::is_reference_v<P>, "systems take their stores by reference");
    if constexpr (std::is_const_v<std::remove_reference_t<P>>) access.reads.push_back(store);
    else access.writes.push_back(store);
  }

  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string name_;
  const StepContext& ctx_;
};

}  // namespace loom
