//! \file command_line_fuzzer.cpp
//! libFuzzer target fuzz_command_line: the `delmesh` front end.  The input is argv, one argument
//! per line (at most 64), after the program name.  The app is configured as in apps/main.cpp (keep
//! the two in step) and parses the arguments as main() does.  Then, with a scratch directory that
//! holds a small octahedron as m.off, m.ply and m.obj as the working directory:
//!   - `surfaces`, `check` and `report` run (check and report only on files of the scratch
//!     directory: no argument may contain '/'; report writes its page there);
//!   - `mesh` and `solve` are not run (they may mesh for minutes and write files), but their
//!     --surface / --expr / --box are resolved as the commands do (SurfaceOptions::resolve).
//! Parsing may only fail with a CLI::ParseError or InvalidInput and a command only with
//! InvalidInput (main() turns both into `error:` and exit 2); anything else is a finding.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <streambuf>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "apps/command_line.h"
#include "fuzz/fuzz_support.h"

namespace {

using delmesh::fuzz::expect_valid_or_invalid_input;

constexpr std::size_t max_arguments = 64;

const char* const octahedron_off =
    "OFF\n6 8 0\n1 0 0\n-1 0 0\n0 1 0\n0 -1 0\n0 0 1\n0 0 -1\n"
    "3 0 2 4\n3 2 1 4\n3 1 3 4\n3 3 0 4\n3 2 0 5\n3 1 2 5\n3 3 1 5\n3 0 3 5\n";
const char* const octahedron_obj =
    "v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n"
    "f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6\n";
const char* const octahedron_ply =
    "ply\nformat ascii 1.0\nelement vertex 6\nproperty double x\nproperty double y\nproperty double z\n"
    "element face 8\nproperty list uchar int vertex_indices\nend_header\n"
    "1 0 0\n-1 0 0\n0 1 0\n0 -1 0\n0 0 1\n0 0 -1\n"
    "3 0 2 4\n3 2 1 4\n3 1 3 4\n3 3 0 4\n3 2 0 5\n3 1 2 5\n3 3 1 5\n3 0 3 5\n";

std::string scratch_directory;

void remove_scratch_directory() {
  std::error_code ec;
  if (!scratch_directory.empty()) std::filesystem::remove_all(scratch_directory, ec);
}

//! Discards everything (std::cout and std::cerr while a command runs).
class NullBuffer : public std::streambuf {
 protected:
  int overflow(int c) override { return traits_type::not_eof(c); }
  std::streamsize xsputn(const char*, std::streamsize n) override { return n; }
};

//! Redirects std::cout and std::cerr to nothing for its lifetime.
class Silence {
 public:
  Silence() : out_(std::cout.rdbuf(&null_)), err_(std::cerr.rdbuf(&null_)) {}
  ~Silence() {
    std::cout.rdbuf(out_);
    std::cerr.rdbuf(err_);
  }
  Silence(const Silence&) = delete;
  Silence& operator=(const Silence&) = delete;

 private:
  NullBuffer null_;
  std::streambuf* out_;
  std::streambuf* err_;
};

//! Makes the scratch directory the working directory for its lifetime (libFuzzer's own paths,
//! given relative to the starting directory, stay valid between inputs).
class InScratchDirectory {
 public:
  InScratchDirectory() : previous_(std::filesystem::current_path()) { change(scratch_directory); }
  ~InScratchDirectory() { change(previous_.string()); }
  InScratchDirectory(const InScratchDirectory&) = delete;
  InScratchDirectory& operator=(const InScratchDirectory&) = delete;

 private:
  static void change(const std::string& directory) {
    if (::chdir(directory.c_str()) != 0) {
      std::perror("fuzz: chdir");
      std::abort();
    }
  }
  std::filesystem::path previous_;
};

//! The surface options as a command received them, resolved as the command would.
void resolve_surface(CLI::App& sub) {
  std::vector<std::string> args;
  for (const char* name : {"--surface", "--expr", "--box"}) {
    const CLI::Option* option = sub.get_option_no_throw(name);
    if (option && option->count() > 0 && !option->results().empty()) {
      args.push_back(std::string(name) + "=" + option->results().back());
    }
  }
  if (args.empty()) return;
  CLI::App shadow{"surface options"};
  delmesh::app::SurfaceOptions surface;
  surface.add_to(shadow);
  std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI::App::parse takes them reversed
  try {
    shadow.parse(reversed);
  } catch (const CLI::ParseError&) {
    return;  // a value the real parse took but this one cannot
  }
  expect_valid_or_invalid_input("SurfaceOptions::resolve", [&] { (void)surface.resolve(); });
}

//! The octahedron as m.off, m.obj and m.ply in the scratch directory (again after a `report`,
//! whose --out may have named one of them).
void write_scratch_meshes() {
  for (const auto& [name, text] : {std::pair{"m.off", octahedron_off}, std::pair{"m.obj", octahedron_obj},
                                   std::pair{"m.ply", octahedron_ply}}) {
    std::ofstream(scratch_directory + "/" + name) << text;
  }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  std::error_code ec;
  std::filesystem::path base =
      std::filesystem::is_directory("/dev/shm", ec) ? std::filesystem::path("/dev/shm") : std::filesystem::temp_directory_path();
  std::string pattern = (base / "delmesh-fuzz-cli-XXXXXX").string();
  if (!::mkdtemp(pattern.data())) {
    std::perror("fuzz: mkdtemp");
    std::abort();
  }
  scratch_directory = pattern;
  std::atexit(remove_scratch_directory);
  write_scratch_meshes();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> arguments{"delmesh"};
  const std::string text(reinterpret_cast<const char*>(data), size);
  bool has_slash = false, has_certify = false;
  for (std::size_t at = 0; at <= text.size() && arguments.size() <= max_arguments;) {
    std::size_t end = text.find('\n', at);
    if (end == std::string::npos) end = text.size();
    arguments.push_back(text.substr(at, end - at));
    has_slash = has_slash || arguments.back().find('/') != std::string::npos;
    has_certify = has_certify || arguments.back().rfind("--certify", 0) == 0;
    at = end + 1;
  }
  std::vector<const char*> argv;
  for (const std::string& a : arguments) argv.push_back(a.c_str());

  // As apps/main.cpp.
  CLI::App app{"delmesh", "delmesh"};
  app.set_version_flag("--version", "delmesh 0.1.0");
  app.require_subcommand(1);
  app.fallthrough(false);
  app.get_formatter()->column_width(34);
  std::vector<delmesh::app::Command> commands;
  commands.push_back(delmesh::app::add_surfaces_command(app));
  commands.push_back(delmesh::app::add_solve_command(app));
  commands.push_back(delmesh::app::add_mesh_command(app));
  commands.push_back(delmesh::app::add_check_command(app));
  commands.push_back(delmesh::app::add_report_command(app));

  const bool parsed = expect_valid_or_invalid_input("CLI::App::parse", [&] {
    try {
      app.parse(static_cast<int>(argv.size()), argv.data());
    } catch (const CLI::ParseError& e) {
      // main(): --help/--version (exit 0) or a usage error (exit 2).
      throw std::invalid_argument(e.what());
    }
  });
  if (!parsed) return 0;

  for (auto& command : commands) {
    if (!command.subcommand->parsed()) continue;
    const std::string name = command.subcommand->get_name();
    Silence silence;
    if (name == "surfaces" || (name == "check" && !has_slash && !has_certify) || (name == "report" && !has_slash)) {
      InScratchDirectory scratch;
      expect_valid_or_invalid_input(name.c_str(), [&] { (void)command.run(); });
      if (name == "report") write_scratch_meshes();
    } else if (name == "mesh" || name == "solve") {
      resolve_surface(*command.subcommand);
    }
  }
  return 0;
}
