#include "engine/io/async_writer.hpp"

#include <future>

namespace loom {

// A std::async thread, not a oneTBB task: a task spawned from one graph node and waited for from a later
// one is not taken by the waiting thread (each graph run executes in its own isolation), so with a single
// oneTBB thread (--threads 1) the wait never ended.
struct AsyncWriter::Impl {
  std::future<void> job;
};

AsyncWriter::AsyncWriter() : impl_(std::make_unique<Impl>()) {}

AsyncWriter::~AsyncWriter() {
  if (impl_->job.valid()) impl_->job.wait();
}

void AsyncWriter::submit(std::function<void()> job) {
  wait();
  impl_->job = std::async(std::launch::async, std::move(job));
}

void AsyncWriter::wait() {
  if (impl_->job.valid()) impl_->job.get();  // rethrows the job's exception, if any
}

}  // namespace loom
