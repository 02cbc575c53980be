// Runs output jobs (VTK frames) concurrently with the next step (DESIGN §4), one job at a time and in
// submission order: submitting waits for the previous job, so at most one snapshot is in flight.
// A job runs on a thread of its own (one writer thread beside oneTBB's --threads; the VTK writer is serial).
#pragma once

#include <exception>
#include <functional>
#include <memory>

namespace loom {

class AsyncWriter {
 public:
  AsyncWriter();
  ~AsyncWriter();  // waits for the job in flight
  AsyncWriter(const AsyncWriter&) = delete;
  AsyncWriter& operator=(const AsyncWriter&) = delete;

  void submit(std::function<void()> job);
  // Waits for the job in flight and rethrows its exception, if any.
  void wait();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace loom
