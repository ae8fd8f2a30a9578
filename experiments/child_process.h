#pragma once
//! \file child_process.h
//! Runs a program as a child process and reports what it printed and the peak resident memory it
//! reached, so that an experiment can measure each mesher's memory alone, in a fresh process,
//! within one run of the experiment.

#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

extern char** environ;

namespace delmesh::experiments {

struct ChildResult {
  int exit_code = -1;             //!< the child's exit status; -1 if a signal ended it
  std::string out;                //!< everything it wrote on stdout (stderr is inherited)
  //! Its peak resident set size (wait4's ru_maxrss, KiB × 1024).  Linux counts there the address
  //! space the child had before its exec as well, and posix_spawn's child runs in the parent's
  //! until then: this is at least the parent's resident size at the spawn.  A child that must
  //! be measured alone reports its own peak (common/peak_memory.h) on stdout.
  std::uint64_t peak_bytes = 0;
};

//! Runs `program` with `arguments` (argv[1..]) and waits for it.  Throws std::runtime_error when
//! the child cannot be started or waited for.
inline ChildResult run_child(const std::string& program, const std::vector<std::string>& arguments) {
  std::vector<char*> argv;
  argv.push_back(const_cast<char*>(program.c_str()));
  for (const std::string& a : arguments) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);

  int pipe_ends[2];
  if (pipe(pipe_ends) != 0) throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, pipe_ends[1], STDOUT_FILENO);
  posix_spawn_file_actions_addclose(&actions, pipe_ends[0]);
  posix_spawn_file_actions_addclose(&actions, pipe_ends[1]);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, program.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(pipe_ends[1]);
  if (spawned != 0) {
    close(pipe_ends[0]);
    throw std::runtime_error("cannot start " + program + ": " + std::strerror(spawned));
  }

  ChildResult result;
  char buffer[4096];
  for (;;) {
    const ssize_t n = read(pipe_ends[0], buffer, sizeof buffer);
    if (n > 0) {
      result.out.append(buffer, static_cast<std::size_t>(n));
    } else if (n == 0 || errno != EINTR) {
      break;
    }
  }
  close(pipe_ends[0]);

  int status = 0;
  rusage usage{};
  while (wait4(pid, &status, 0, &usage) < 0) {
    if (errno != EINTR) throw std::runtime_error(std::string("wait4: ") + std::strerror(errno));
  }
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.peak_bytes = usage.ru_maxrss > 0 ? static_cast<std::uint64_t>(usage.ru_maxrss) * 1024 : 0;
  return result;
}

}  // namespace delmesh::experiments
