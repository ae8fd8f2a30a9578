#include "apps/phase_watchdog.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>

#include "apps/command_line.h"

namespace delmesh::app {

std::string stop_message(StopReason reason, const std::string& phase) {
  return one_line(std::string(reason == StopReason::interrupted ? "interrupted by a signal (status interrupted)"
                                                                : "stopped by --time-limit (status time_limit)") +
                  " while " + phase + "; no output written");
}

ExitCode stopped_as_limit(const std::function<ExitCode()>& action) {
  try {
    return action();
  } catch (const RunStopped& stopped) {
    print_warning(stop_message(stopped.reason(), stopped.phase()));
    return ExitCode::limit_reached;
  }
}

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
    const std::string line = "warning: " + stop_message(reason, phase_) + "\n";
    std::fflush(stdout);
    std::fflush(stderr);
    const ssize_t written = ::write(STDERR_FILENO, line.data(), line.size());
    (void)written;
    std::_Exit(static_cast<int>(ExitCode::limit_reached));
  }
}

}  // namespace delmesh::app
