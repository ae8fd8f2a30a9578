#pragma once
//! \file deadline.h
//! The time budget of one solve (internal; shared by the univariate isolator and the subdivision
//! solver): expired() is true once more than `seconds` (> 0; 0 means no budget) have passed since
//! `start`.  The clock is read once every clock_check_interval calls, since a read costs about as
//! much as examining a box; once true it stays true.

#include <chrono>

namespace delmesh::detail {

class Deadline {
 public:
  static constexpr int clock_check_interval = 16;

  Deadline(std::chrono::steady_clock::time_point start, double seconds) : start_(start), seconds_(seconds) {}

  bool expired() {
    if (expired_ || seconds_ <= 0) return expired_;
    if (++calls_ < clock_check_interval) return false;
    calls_ = 0;
    expired_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count() > seconds_;
    return expired_;
  }

 private:
  std::chrono::steady_clock::time_point start_;
  double seconds_;
  int calls_ = 0;
  bool expired_ = false;
};

}  // namespace delmesh::detail
