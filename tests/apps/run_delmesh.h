#pragma once
//! Runs the built `delmesh` binary (compile definition DELMESH_BINARY) in a scratch directory and
//! captures its exit code, stdout and stderr.  Shared by the tests of tests/apps.

#include <fcntl.h>
#include <grp.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <boost/test/unit_test.hpp>

#include "tests/temp_dir.h"

namespace delmesh::test {

//! The regular octahedron as an outward-oriented OFF file: genus 0, angles 60°, radius-edge ratio
//! 1/√3, dihedral angle acos(−1/3), so roughness π − acos(−1/3) ≈ 1.231 rad.
inline const char* const octahedron_off =
    "OFF\n6 8 0\n"
    "1 0 0\n-1 0 0\n0 1 0\n0 -1 0\n0 0 1\n0 0 -1\n"
    "3 0 2 4\n3 2 1 4\n3 1 3 4\n3 3 0 4\n3 2 0 5\n3 1 2 5\n3 3 1 5\n3 0 3 5\n";

struct RunResult {
  int exit_code = -1;      //!< the program's exit status
  bool signalled = false;  //!< it died by a signal (never allowed)
  std::string out, err;
  //! The lines of stderr.
  std::vector<std::string> err_lines() const {
    std::vector<std::string> lines;
    std::istringstream s(err);
    for (std::string line; std::getline(s, line);) lines.push_back(line);
    return lines;
  }
  //! True iff stderr is exactly one line and it begins with "error:".
  bool single_error_line() const {
    const auto lines = err_lines();
    return lines.size() == 1 && lines[0].rfind("error:", 0) == 0;
  }
};

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

inline std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) {
    if (c == '\'') {
      q += "'\\''";
    } else {
      q += c;
    }
  }
  return q + "'";
}

//! Runs `delmesh args...` with `directory` as working directory.
inline RunResult run_delmesh(const std::vector<std::string>& args, const std::filesystem::path& directory) {
  const std::filesystem::path out_file = directory / ".run.stdout", err_file = directory / ".run.stderr";
  std::string command = "cd " + shell_quote(directory.string()) + " && exec " + shell_quote(DELMESH_BINARY);
  for (const std::string& a : args) command += " " + shell_quote(a);
  command += " > " + shell_quote(out_file.string()) + " 2> " + shell_quote(err_file.string()) + " < /dev/null";
  const int status = std::system(command.c_str());
  RunResult r;
  if (status != -1 && WIFEXITED(status)) {
    r.exit_code = WEXITSTATUS(status);
  }
  r.signalled = status == -1 || WIFSIGNALED(status);
  r.out = read_text(out_file);
  r.err = read_text(err_file);
  std::filesystem::remove(out_file);
  std::filesystem::remove(err_file);
  return r;
}

//! Runs in a throw-away scratch directory.
inline RunResult run_delmesh(const std::vector<std::string>& args) {
  TempDir scratch;
  return run_delmesh(args, scratch.path);
}

//! Starts `delmesh args...` in `directory` without waiting: stdin from /dev/null, stderr to
//! directory/.spawn.stderr, stdout to the descriptor `stdout_fd` if it is not negative, else to
//! directory/.spawn.stdout.  With a non-zero `user` (the caller being root), the program runs as
//! that user and group.  Returns the process id (the child does only async-signal-safe work
//! between fork and exec).
inline pid_t spawn_delmesh(const std::vector<std::string>& args, const std::filesystem::path& directory,
                           int stdout_fd = -1, uid_t user = 0) {
  std::vector<std::string> argv_text{DELMESH_BINARY};
  argv_text.insert(argv_text.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_text) argv.push_back(a.data());
  argv.push_back(nullptr);
  const std::string dir = directory.string(), out = (directory / ".spawn.stdout").string(),
                    err = (directory / ".spawn.stderr").string();
  const pid_t pid = ::fork();
  if (pid == 0) {
    if (::chdir(dir.c_str()) != 0) ::_exit(127);
    const int null = ::open("/dev/null", O_RDONLY);
    const int out_fd = stdout_fd >= 0 ? stdout_fd : ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err_fd = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (null < 0 || out_fd < 0 || err_fd < 0) ::_exit(127);
    ::dup2(null, 0);
    ::dup2(out_fd, 1);
    ::dup2(err_fd, 2);
    if (user != 0 && (::setgroups(0, nullptr) != 0 || ::setgid(user) != 0 || ::setuid(user) != 0)) ::_exit(126);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  return pid;
}

//! Waits for a process of spawn_delmesh() and returns its result (stdout is read from
//! directory/.spawn.stdout, empty if it went elsewhere); removes the two capture files.
inline RunResult wait_delmesh(pid_t pid, const std::filesystem::path& directory) {
  int status = 0;
  RunResult r;
  if (::waitpid(pid, &status, 0) != pid) return r;
  if (WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
  r.signalled = WIFSIGNALED(status);
  r.out = read_text(directory / ".spawn.stdout");
  r.err = read_text(directory / ".spawn.stderr");
  std::error_code ignored;
  std::filesystem::remove(directory / ".spawn.stdout", ignored);
  std::filesystem::remove(directory / ".spawn.stderr", ignored);
  return r;
}

//! Whether process `pid` runs the delmesh binary (it has passed exec) and has a handler for
//! `signal` (bit signal - 1 of the mask on the SigCgt line of /proc/pid/status).
inline bool handler_installed(pid_t pid, int signal) {
  std::error_code error;
  const auto exe = std::filesystem::read_symlink("/proc/" + std::to_string(pid) + "/exe", error);
  if (error || std::filesystem::weakly_canonical(exe, error) != std::filesystem::weakly_canonical(DELMESH_BINARY, error))
    return false;
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("SigCgt:", 0) == 0) return (std::stoull(line.substr(7), nullptr, 16) >> (signal - 1)) & 1u;
  return false;
}

//! Waits (polling every 0.2 ms, at most 20 s) until process `pid` has a handler for `signal`;
//! false if it ended or the time ran out first.
inline bool wait_for_handler(pid_t pid, int signal) {
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (!handler_installed(pid, signal)) {
    siginfo_t info{};
    if (::waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOHANG | WNOWAIT) == 0 && info.si_pid == pid)
      return false;
    if (std::chrono::steady_clock::now() > give_up) return false;
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  return true;
}

//! The names in `directory` that contain ".tmp" (temporary files left behind).
inline std::vector<std::string> temporaries_in(const std::filesystem::path& directory) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(directory)) {
    const std::string name = entry.path().filename().string();
    if (name.find(".tmp") != std::string::npos) names.push_back(name);
  }
  return names;
}

//! Asserts exit code 2 with exactly one stderr line beginning "error:", that mentions `mention`.
inline void require_invalid_input(const RunResult& r, const std::string& mention = {}) {
  BOOST_TEST(!r.signalled);
  BOOST_TEST(r.exit_code == 2);
  BOOST_TEST(r.single_error_line(), "stderr: " << r.err);
  if (!mention.empty()) BOOST_TEST(r.err.find(mention) != std::string::npos, "stderr: " << r.err);
}

}  // namespace delmesh::test
