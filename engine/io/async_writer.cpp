#include "engine/io/async_writer.hpp"

#include <oneapi/tbb/task_group.h>

namespace loom {

struct AsyncWriter::Impl {
  oneapi::tbb::task_group group;
  std::exception_ptr error;
  bool busy = false;
};

AsyncWriter::AsyncWriter() : impl_(std::make_unique<Impl>()) {}

AsyncWriter::~AsyncWriter() {
  if (impl_->busy) impl_->group.wait();
}

void AsyncWriter::submit(std::function<void()> job) {
  wait();
  impl_->busy = true;
  Impl* impl = impl_.get();
  impl_->group.run([impl, job = std::move(job)]() {
    try {
      job();
    } catch (...) {
      impl->error = std::current_exception();
    }
  });
}

void AsyncWriter::wait() {
  if (impl_->busy) {
    impl_->group.wait();
    impl_->busy = false;
  }
  if (impl_->error) {
    auto e = impl_->error;
    impl_->error = nullptr;
    std::rethrow_exception(e);
  }
}

}  // namespace loom
