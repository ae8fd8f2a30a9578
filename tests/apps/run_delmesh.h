#pragma once
//! Runs the built `delmesh` binary (compile definition DELMESH_BINARY) in a scratch directory and
//! captures its exit code, stdout and stderr.  Shared by the tests of tests/apps.

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <string>
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

//! Asserts exit code 2 with exactly one stderr line beginning "error:", that mentions `mention`.
inline void require_invalid_input(const RunResult& r, const std::string& mention = {}) {
  BOOST_TEST(!r.signalled);
  BOOST_TEST(r.exit_code == 2);
  BOOST_TEST(r.single_error_line(), "stderr: " << r.err);
  if (!mention.empty()) BOOST_TEST(r.err.find(mention) != std::string::npos, "stderr: " << r.err);
}

}  // namespace delmesh::test
