#include "apps/phase_watchdog.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>

#include "apps/command_line.h"

namespace delmesh::app {

PhaseWatchdog::PhaseWatchdog(const RunLimits& limits) : limits_(limits) {
  if (!limits_.unlimited()) thread_ = std::thread([this] { watch(); });
}

PhaseWatchdog::~PhaseWatchdog() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void PhaseWatchdog::arm(const std::string& phase) {
  std::lock_guard<std::mutex> lock(mutex_);
  phase_ = phase;
}

void PhaseWatchdog::disarm() {
  std::lock_guard<std::mutex> lock(mutex_);
  phase_.clear();
}

void PhaseWatchdog::watch() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stop_) {
    wake_.wait_for(lock, poll_interval);
    if (stop_ || phase_.empty()) continue;
    const StopReason reason = limits_.expired_now();
    if (reason == StopReason::none) continue;
    // The lock stays held: the main thread cannot disarm and go on to write its outputs.
    const std::string line =
        "warning: " +
        one_line(std::string(reason == StopReason::interrupted ? "interrupted by a signal (status interrupted)"
                                                               : "stopped by --time-limit (status time_limit)") +
                 " while " + phase_ + "; no output written") +
        "\n";
    std::fflush(stdout);
    std::fflush(stderr);
    const ssize_t written = ::write(STDERR_FILENO, line.data(), line.size());
    (void)written;
    std::_Exit(static_cast<int>(ExitCode::limit_reached));
  }
}

}  // namespace delmesh::app
