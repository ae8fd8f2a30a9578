#include "apps/interrupt.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace delmesh::app {

namespace {

std::atomic<bool> interrupted{false};
std::atomic<int> first_signal{0};
std::atomic<int> deferrals{0};
std::atomic<bool> exit_pending{false};
std::atomic<int> pending_signal{0};
static_assert(std::atomic<bool>::is_always_lock_free && std::atomic<int>::is_always_lock_free,
              "the signal handler needs lock-free atomics");

//! A registered temporary: `path` is written before `active` is set and read only while it is.
struct TemporarySlot {
  std::atomic<bool> claimed{false};
  std::atomic<bool> active{false};
  char path[4096] = {};
};
std::array<TemporarySlot, max_registered_temporaries> temporaries;

const char* signal_name(int signal) {
  switch (signal) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    case SIGHUP: return "SIGHUP";
    case SIGQUIT: return "SIGQUIT";
    case SIGXCPU: return "SIGXCPU";
    case SIGUSR1: return "SIGUSR1";
    case SIGUSR2: return "SIGUSR2";
    case SIGALRM: return "SIGALRM";
    default: return "a signal";
  }
}

void write_stderr(const char* text) {
  std::size_t left = std::strlen(text);
  while (left > 0) {
    const ssize_t written = ::write(STDERR_FILENO, text, left);
    if (written <= 0) return;
    text += written;
    left -= static_cast<std::size_t>(written);
  }
}

//! The end after a second signal: temporaries removed, one line on stderr, exit code 3.
[[noreturn]] void stop_now(int signal) {
  remove_registered_temporaries();
  write_stderr("error: stopped at once by a second signal (");
  write_stderr(signal_name(signal));
  write_stderr("); temporary files removed, outputs not yet replaced are left as they were\n");
  ::_exit(3);
}

extern "C" void on_interrupt(int signal) {
  const int saved_errno = errno;
  int none = 0;
  first_signal.compare_exchange_strong(none, signal);
  if (interrupted.exchange(true)) {
    if (deferrals.load() > 0) {
      pending_signal.store(signal);
      exit_pending.store(true);
      // The last DeferredExit may have ended between the two loads: then nobody else will act.
      if (deferrals.load() > 0) {
        errno = saved_errno;
        return;
      }
    }
    stop_now(signal);
  }
  errno = saved_errno;
}

}  // namespace

void install_interrupt_handlers() {
  struct sigaction action {};
  action.sa_handler = on_interrupt;
  sigemptyset(&action.sa_mask);
  // Blocking the other interrupt signals while the handler runs keeps two signals that arrive
  // together from racing through it.
  for (int signal : interrupt_signals) sigaddset(&action.sa_mask, signal);
  action.sa_flags = SA_RESTART;
  for (int signal : interrupt_signals) ::sigaction(signal, &action, nullptr);
  struct sigaction ignore {};
  ignore.sa_handler = SIG_IGN;
  sigemptyset(&ignore.sa_mask);
  ::sigaction(SIGPIPE, &ignore, nullptr);
}

const std::atomic<bool>& interrupt_flag() { return interrupted; }

std::string interrupt_signal_name() {
  const int signal = first_signal.load();
  return signal == 0 ? std::string() : std::string(signal_name(signal));
}

std::size_t register_temporary(const std::string& path) {
  if (path.size() >= sizeof(TemporarySlot::path))
    throw std::length_error("temporary file name too long: " + path);
  for (std::size_t slot = 0; slot < temporaries.size(); ++slot) {
    bool expected = false;
    if (!temporaries[slot].claimed.compare_exchange_strong(expected, true)) continue;
    std::memcpy(temporaries[slot].path, path.c_str(), path.size() + 1);
    temporaries[slot].active.store(true);
    return slot;
  }
  throw std::length_error("more than " + std::to_string(max_registered_temporaries) + " temporary files at once");
}

void unregister_temporary(std::size_t slot) {
  if (slot >= temporaries.size()) return;
  temporaries[slot].active.store(false);
  temporaries[slot].claimed.store(false);
}

void remove_registered_temporaries() noexcept {
  for (TemporarySlot& slot : temporaries) {
    if (slot.active.exchange(false)) ::unlink(slot.path);
  }
}

DeferredExit::DeferredExit() { deferrals.fetch_add(1); }

DeferredExit::~DeferredExit() {
  if (deferrals.fetch_sub(1) == 1 && exit_pending.load()) stop_now(pending_signal.load());
}

}  // namespace delmesh::app
