#include "engine/core/interrupt.hpp"

#include <unistd.h>

#include <atomic>
#include <csignal>

namespace loom {
namespace {

std::atomic<int> g_signal{0};  // lock-free: read and written from the handler
int (*g_agree)(int) = nullptr;

extern "C" void on_signal(int sig) {
  if (g_signal.exchange(sig) != 0) {  // the second signal: stop now
    std::signal(sig, SIG_DFL);
    std::raise(sig);
    return;
  }
  // write() is async-signal-safe; the message says what will happen.
  static const char msg[] =
      "\nloom: stopping after the current step (run.json, timings.json and a checkpoint, if enabled, are written); "
      "signal again to stop at once\n";
  [[maybe_unused]] const ssize_t n = write(STDERR_FILENO, msg, sizeof msg - 1);
}

}  // namespace

void install_interrupt_handlers() {
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;  // the writer's and the solver's system calls go on
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

bool interrupt_requested() { return g_signal.load(std::memory_order_relaxed) != 0; }
int interrupt_signal() { return g_signal.load(std::memory_order_relaxed); }
void request_interrupt(int signal) { g_signal.store(signal); }
void clear_interrupt() { g_signal.store(0); }
void set_interrupt_agreement(int (*agree)(int)) { g_agree = agree; }
int agreed_interrupt_signal() { return g_agree ? g_agree(interrupt_signal()) : interrupt_signal(); }

const char* signal_name(int signal) {
  switch (signal) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    default: return "a signal";
  }
}

}  // namespace loom
