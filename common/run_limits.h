#pragma once
//! \file run_limits.h
//! The limits of one command: a deadline on the steady clock (from --time-limit) and the
//! interrupt flag a signal handler sets (apps/interrupt.h).  One RunLimits is made when a command
//! starts and handed to each of its long phases (parsing and symbolic work, reading and
//! validating an input, building an oracle, refinement, the certificate); each tests it between
//! its steps.
//!
//! A phase with a partial result (refinement: a partial mesh; the certificate: an undecided
//! one) stops and reports it through its status.  A phase before any result exists (parsing,
//! differentiation, reading or validating an input, building an oracle) has nothing to return:
//! it throws RunStopped, which the command turns into its status time_limit or interrupted and
//! exit code 3, with one warning line and no output files.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>

namespace delmesh {

//! Why a run stopped early (none: it did not).
enum class StopReason { none, time_limit, interrupted };

//! Thrown by a phase that has no partial result when the run's limit passes.  what(): "stopped
//! by the time limit while <phase>" or "interrupted by a signal while <phase>".
class RunStopped : public std::runtime_error {
 public:
  RunStopped(StopReason reason, const std::string& phase)
      : std::runtime_error(std::string(reason == StopReason::interrupted ? "interrupted by a signal" : "stopped by the time limit") +
                           " while " + phase),
        reason_(reason), phase_(phase) {}
  StopReason reason() const { return reason_; }
  const std::string& phase() const { return phase_; }

 private:
  StopReason reason_;
  std::string phase_;
};

class RunLimits {
 public:
  using Clock = std::chrono::steady_clock;

  //! How many calls of expired() share one clock reading (the interrupt flag is read on every
  //! call).  A call costs a relaxed atomic load and a counter increment; a loop whose step takes
  //! at least a microsecond sees the deadline at most this many steps late.
  static constexpr std::uint32_t calls_per_clock_reading = 32;

  //! No deadline and no interrupt flag: expired() is always none.
  RunLimits() = default;
  RunLimits(std::optional<Clock::time_point> deadline, const std::atomic<bool>* interrupt)
      : deadline_(deadline), interrupt_(interrupt) {}
  //! A deadline `seconds` after `start` (none if seconds ≤ 0) and the flag `interrupt` (may be null).
  static RunLimits after(double seconds, const std::atomic<bool>* interrupt, Clock::time_point start = Clock::now()) {
    std::optional<Clock::time_point> deadline;
    if (seconds > 0)
      deadline = start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
    return RunLimits(deadline, interrupt);
  }

  const std::optional<Clock::time_point>& deadline() const { return deadline_; }
  const std::atomic<bool>* interrupt() const { return interrupt_; }
  bool unlimited() const { return !deadline_ && !interrupt_; }

  //! interrupted once the flag reads true, time_limit once the deadline has passed (the clock
  //! is read on every calls_per_clock_reading-th call and after the deadline was seen), else none.
  //! Not thread-safe: a thread of its own uses its own copy.
  StopReason expired() const {
    if (interrupt_ && interrupt_->load(std::memory_order_relaxed)) return StopReason::interrupted;
    if (!deadline_) return StopReason::none;
    if (passed_ || ++calls_ % calls_per_clock_reading == 0) return expired_now();
    return StopReason::none;
  }
  //! expired() with a clock reading now: for a loop whose steps are long (a GiNaC operation).
  StopReason expired_now() const {
    if (interrupt_ && interrupt_->load(std::memory_order_relaxed)) return StopReason::interrupted;
    if (deadline_ && (passed_ || Clock::now() >= *deadline_)) {
      passed_ = true;
      return StopReason::time_limit;
    }
    return StopReason::none;
  }
  //! Throws RunStopped naming `phase` if expired() (with `now`: expired_now()).
  void check(const char* phase, bool now = false) const {
    const StopReason reason = now ? expired_now() : expired();
    if (reason != StopReason::none) throw RunStopped(reason, phase);
  }

  //! The limits of the command running on this thread: those of the innermost live Scope, else
  //! none.  Phases reached through interfaces that carry no limits of their own (parsing,
  //! reading and validating an input, building an oracle) read them here.
  static const RunLimits& current() {
    static const RunLimits none;
    return current_ ? *current_ : none;
  }
  //! Makes `limits` current() on this thread for its lifetime.  `limits` must outlive it.
  class Scope {
   public:
    explicit Scope(const RunLimits& limits) : previous_(current_) { current_ = &limits; }
    ~Scope() { current_ = previous_; }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    const RunLimits* previous_;
  };

  //! Seconds left before the deadline (negative once passed); nothing without a deadline.
  std::optional<double> seconds_left() const {
    if (!deadline_) return std::nullopt;
    return std::chrono::duration<double>(*deadline_ - Clock::now()).count();
  }

 private:
  std::optional<Clock::time_point> deadline_;
  const std::atomic<bool>* interrupt_ = nullptr;
  mutable std::uint32_t calls_ = 0;
  mutable bool passed_ = false;
  static inline thread_local const RunLimits* current_ = nullptr;
};

}  // namespace delmesh
