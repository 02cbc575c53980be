// Text description of a store's columns: name, entries and memory; absent columns are listed as such.
#pragma once

#include <cstddef>
#include <ostream>
#include <string>

namespace loom {

class StoreReport {
 public:
  StoreReport(std::ostream& os, std::string store, long long entities)
      : os_(os), store_(std::move(store)), entities_(entities) {}

  template <class ColumnT>
  void operator()(const char* name, const ColumnT& c) {
    if (c.used()) {
      used_ += std::string(used_.empty() ? "" : ", ") + name;
      bytes_ += c.bytes();
    } else {
      unused_ += std::string(unused_.empty() ? "" : ", ") + name;
    }
  }

  ~StoreReport() {
    os_ << "  " << store_ << ": " << entities_ << " entities, " << bytes_ / 1024 << " KiB\n"
        << "    columns: " << (used_.empty() ? "-" : used_) << "\n";
    if (!unused_.empty()) os_ << "    not allocated: " << unused_ << "\n";
  }

 private:
  std::ostream& os_;
  std::string store_;
  long long entities_;
  std::string used_, unused_;
  std::size_t bytes_ = 0;
};

}  // namespace loom
