// Step graph (engine/graph/step_graph): edges follow from declared reads and writes (transitively
// reduced), add_system derives access from the constness of the system's parameters, nodes run in
// dependency order, run_if skips a node without blocking its successors, and an exception in a node is
// rethrown by run() naming the node, with the nodes after it skipped.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <mutex>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "engine/core/errors.hpp"
#include "engine/graph/step_graph.hpp"

namespace loom {
namespace {

using Edge = std::pair<std::string, std::string>;

std::set<Edge> edge_set(const StepGraph& g) {
  const auto e = g.edges();
  return {e.begin(), e.end()};
}

// Records the order in which node bodies ran (bodies may run on several threads).
struct Log {
  std::mutex mutex;
  std::vector<std::string> order;
  std::function<void()> add(std::string name) {
    return [this, name] {
      std::lock_guard lock(mutex);
      order.push_back(name);
    };
  }
  std::size_t position(const std::string& name) const {
    return std::size_t(std::find(order.begin(), order.end(), name) - order.begin());
  }
  bool ran(const std::string& name) const { return position(name) < order.size(); }
};

struct Fixture {
  StepContext ctx;
  Timers timers;
  StepGraph graph{"test", ctx, timers};
  int x = 0, y = 0, z = 0;  // stand-ins for stores: only their addresses matter to the graph
};

// Systems for add_system: the signature declares the access.
void produce_x(const StepContext& ctx, int& x) { x = 10 * ctx.step; }
void square_x_into_y(const StepContext&, const int& x, int& y) { y = x * x; }
void sum_into_z(const StepContext&, const int& x, const int& y, int& z) { z = x + y; }

}  // namespace

TEST(StepGraph, EdgesFollowFromReadsAndWritesTransitivelyReduced) {
  Fixture f;
  Log log;
  // A writes x; B reads x, writes y; C reads x; D reads y and x.
  f.graph.add_node("A", {{}, {&f.x}}, log.add("A"));
  f.graph.add_node("B", {{&f.x}, {&f.y}}, log.add("B"));
  f.graph.add_node("C", {{&f.x}, {}}, log.add("C"));
  f.graph.add_node("D", {{&f.y, &f.x}, {}}, log.add("D"));
  f.graph.build();
  // A -> D is implied by A -> B -> D; C and D only read x after A: no edge between them.
  EXPECT_EQ(edge_set(f.graph), (std::set<Edge>{{"A", "B"}, {"A", "C"}, {"B", "D"}}));
}

TEST(StepGraph, WriteAfterReadAndWriteAfterWriteAreOrdered) {
  Fixture f;
  f.graph.add_node("reader", {{&f.x}, {}}, [] {});
  f.graph.add_node("writer", {{}, {&f.x}}, [] {});        // after reader (write after read)
  f.graph.add_node("rewriter", {{}, {&f.x}}, [] {});      // after writer (write after write)
  f.graph.add_node("unrelated", {{&f.y}, {&f.z}}, [] {});  // independent
  f.graph.build();
  EXPECT_EQ(edge_set(f.graph), (std::set<Edge>{{"reader", "writer"}, {"writer", "rewriter"}}));
}

TEST(StepGraph, ReadersOfOneStoreAreIndependent) {
  Fixture f;
  f.graph.add_node("r1", {{&f.x}, {}}, [] {});
  f.graph.add_node("r2", {{&f.x}, {&f.y}}, [] {});
  f.graph.add_node("r3", {{&f.x}, {&f.z}}, [] {});
  f.graph.build();
  EXPECT_TRUE(f.graph.edges().empty());
}

TEST(StepGraph, AddSystemTakesAccessFromParameterConstness) {
  Fixture f;
  f.graph.add_system("produce", &produce_x, f.x);
  f.graph.add_system("square", &square_x_into_y, f.x, f.y);
  f.graph.add_system("sum", &sum_into_z, f.x, f.y, f.z);
  f.graph.build();
  EXPECT_EQ(edge_set(f.graph), (std::set<Edge>{{"produce", "square"}, {"square", "sum"}}));
  // The systems see the graph's context at run time.
  f.ctx.step = 3;
  f.graph.run();
  EXPECT_EQ(f.x, 30);
  EXPECT_EQ(f.y, 900);
  EXPECT_EQ(f.z, 930);
  f.ctx.step = 1;
  f.graph.run();
  EXPECT_EQ(f.z, 10 + 100);
}

TEST(StepGraph, NodesRunInDependencyOrder) {
  Fixture f;
  Log log;
  int w = 0;
  // A diamond A -> (B, C) -> D followed by E, run several times.
  f.graph.add_node("A", {{}, {&f.x}}, log.add("A"));
  f.graph.add_node("B", {{&f.x}, {&f.y}}, log.add("B"));
  f.graph.add_node("C", {{&f.x}, {&f.z}}, log.add("C"));
  f.graph.add_node("D", {{&f.y, &f.z}, {&w}}, log.add("D"));
  f.graph.add_node("E", {{&w}, {}}, log.add("E"));
  f.graph.build();
  for (int run = 0; run < 20; ++run) {
    log.order.clear();
    f.graph.run();
    ASSERT_EQ(log.order.size(), 5u);
    EXPECT_EQ(log.order.front(), "A");
    EXPECT_LT(log.position("B"), log.position("D"));
    EXPECT_LT(log.position("C"), log.position("D"));
    EXPECT_EQ(log.order[3], "D");
    EXPECT_EQ(log.order.back(), "E");
  }
}

TEST(StepGraph, RunIfSkipsTheNodeButItsSuccessorsRun) {
  Fixture f;
  Log log;
  bool enabled = false;
  f.graph.add_node("A", {{}, {&f.x}}, log.add("A"));
  const auto b = f.graph.add_node("B", {{&f.x}, {&f.y}}, log.add("B"));
  f.graph.add_node("C", {{&f.y}, {}}, log.add("C"));
  f.graph.run_if(b, &f.z, [&] { return enabled; });
  f.graph.build();
  // The predicate's store is a read of B: B now also waits for writers of z (none here).
  EXPECT_EQ(edge_set(f.graph), (std::set<Edge>{{"A", "B"}, {"B", "C"}}));
  f.graph.run();
  EXPECT_TRUE(log.ran("A"));
  EXPECT_FALSE(log.ran("B"));
  EXPECT_TRUE(log.ran("C"));
  // The predicate is evaluated at every run.
  log.order.clear();
  enabled = true;
  f.graph.run();
  EXPECT_EQ(log.order, (std::vector<std::string>{"A", "B", "C"}));
}

TEST(StepGraph, RunIfReadOrdersTheNodeAfterTheWriterOfThePredicateStore) {
  Fixture f;
  f.graph.add_node("status", {{}, {&f.z}}, [] {});
  const auto commit = f.graph.add_node("commit", {{}, {&f.x}}, [] {});
  f.graph.run_if(commit, &f.z, [] { return true; });
  f.graph.build();
  EXPECT_EQ(edge_set(f.graph), (std::set<Edge>{{"status", "commit"}}));
}

TEST(StepGraph, ExceptionIsRethrownNamingTheNodeAndLaterNodesAreSkipped) {
  Fixture f;
  Log log;
  bool fail = true;
  f.graph.add_node("first", {{}, {&f.x}}, log.add("first"));
  f.graph.add_node("breaker", {{&f.x}, {&f.y}}, [&] {
    if (fail) throw std::runtime_error("boom");
  });
  f.graph.add_node("after", {{&f.y}, {}}, log.add("after"));
  f.graph.build();
  try {
    f.graph.run();
    FAIL() << "run() did not throw";
  } catch (const RunError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("breaker"), std::string::npos) << msg;
    EXPECT_NE(msg.find("boom"), std::string::npos) << msg;
  }
  EXPECT_TRUE(log.ran("first"));
  EXPECT_FALSE(log.ran("after"));
  // The error does not stick: the next run goes through.
  fail = false;
  log.order.clear();
  f.graph.run();
  EXPECT_EQ(log.order, (std::vector<std::string>{"first", "after"}));
}

TEST(StepGraph, RunErrorOfANodeKeepsItsMessage) {
  Fixture f;
  f.graph.add_node("solver", {{}, {&f.x}}, [] { throw RunError("Newton gave up"); });
  f.graph.build();
  try {
    f.graph.run();
    FAIL() << "run() did not throw";
  } catch (const RunError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("solver"), std::string::npos) << msg;
    EXPECT_NE(msg.find("Newton gave up"), std::string::npos) << msg;
  }
}

TEST(StepGraph, NodesAreTimedUnderTheirNames) {
  Fixture f;
  f.graph.add_node("assemble", {{}, {&f.x}}, [] {});
  f.graph.add_node("solve", {{&f.x}, {}}, [] {});
  f.graph.build();
  f.graph.run();
  f.graph.run();
  const auto stats = f.timers.snapshot();
  ASSERT_TRUE(stats.count("assemble"));
  ASSERT_TRUE(stats.count("solve"));
  EXPECT_EQ(stats.at("assemble").calls, 2);
  EXPECT_EQ(stats.at("solve").calls, 2);
}

TEST(StepGraph, PrintNamesNodesStoresAndPredecessors) {
  Fixture f;
  f.graph.name_store(&f.x, "nodes");
  f.graph.add_node("assemble", {{}, {&f.x}}, [] {}, "colour by colour");
  f.graph.add_node("solve", {{&f.x}, {}}, [] {});
  f.graph.build();
  std::ostringstream os;
  f.graph.print(os);
  const std::string s = os.str();
  EXPECT_NE(s.find("'test': 2 nodes"), std::string::npos) << s;
  EXPECT_NE(s.find("colour by colour"), std::string::npos) << s;
  EXPECT_NE(s.find("writes: nodes"), std::string::npos) << s;
  EXPECT_NE(s.find("after: assemble"), std::string::npos) << s;
  EXPECT_NE(s.find("after: (start)"), std::string::npos) << s;
  EXPECT_EQ(f.graph.size(), 2u);
}

}  // namespace loom
