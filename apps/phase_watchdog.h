#pragma once
//! \file phase_watchdog.h
//! The command's limits (common/run_limits.h) over the phases that cannot test them between
//! steps of their own: GiNaC's parsing, differentiation and expansion of E and the compilation of
//! its systems (one GiNaC call may run for minutes on a large expression, and nothing inside it
//! can be asked to stop), and the reading, validation and oracle construction that precede them.
//! While a phase is armed, a thread of the watchdog reads the limits every
//! PhaseWatchdog::poll_interval; once they have passed it ends the process: one warning line
//! "warning: stopped by --time-limit (status time_limit) while <phase>; no output written" (or
//! "interrupted by a signal (status interrupted) …") and exit code 3.  Such a phase writes no file,
//! and the outputs are replaced atomically (command_line.h), so nothing is left half written.
//! Only the program arms it: the Python module calls the same computations without it.
//! A phase that tests the limits itself (Surface between its GiNaC steps, the compilation of a
//! system between its nodes) may see them first and throw RunStopped: stopped_as_limit() ends
//! the command the same way.

#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

#include "apps/command_line.h"
#include "common/run_limits.h"

namespace delmesh::app {

//! "stopped by --time-limit (status time_limit) while <phase>; no output written", or
//! "interrupted by a signal (status interrupted) while …": the warning of a stop before any output.
std::string stop_message(StopReason reason, const std::string& phase);

//! Runs a command's action; a RunStopped it throws becomes the warning stop_message() and exit
//! code 3, as the watchdog would have ended it.
ExitCode stopped_as_limit(const std::function<ExitCode()>& action);

class PhaseWatchdog {
 public:
  static constexpr std::chrono::milliseconds poll_interval{10};
  //! How long after the deadline `delmesh solve` is left to stop by itself (the solver reads the
  //! deadline; compiling E does not) before the watchdog ends it.
  static constexpr std::chrono::duration<double> solve_grace{1.0};

  //! Watches `limits` (copied); starts no thread if they are unlimited.
  explicit PhaseWatchdog(const RunLimits& limits);
  ~PhaseWatchdog();
  PhaseWatchdog(const PhaseWatchdog&) = delete;
  PhaseWatchdog& operator=(const PhaseWatchdog&) = delete;

  //! Arms the watchdog for `phase` ("compiling the expression"), replacing an armed phase.
  void arm(const std::string& phase);
  //! Disarms it: once this returns, the watchdog does not end the process until armed again.
  void disarm();

  //! Arms the watchdog for its lifetime.
  class Phase {
   public:
    Phase(PhaseWatchdog& watchdog, const std::string& phase) : watchdog_(watchdog) { watchdog_.arm(phase); }
    ~Phase() { watchdog_.disarm(); }
    Phase(const Phase&) = delete;
    Phase& operator=(const Phase&) = delete;

   private:
    PhaseWatchdog& watchdog_;
  };

 private:
  void watch();

  RunLimits limits_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::string phase_;  //!< the armed phase; empty: disarmed
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace delmesh::app
