//! \file output_paths_fuzzer.cpp
//! libFuzzer target fuzz_output_paths: the command line's output files (apps/output_files.h,
//! OutputSet: what `delmesh mesh` does with --out and --stats) on fuzzed path names.
//!
//! The input is up to three path names, one per line (a final line break ends the last) (--out, --stats, and a third output, as a
//! command with more outputs would add).  Each input runs in a fresh copy of a private scratch
//! tree under a directory made by mkdtemp:
//!   <root>/outside/in/        o.off, o.json, and dir/ holding f.json: files outside the working
//!                             directory, reached only through the links below or "..";
//!   <root>/work/a/b/          the working directory: a.off, a.json, h.off (a hard link to a.off),
//!                             d/ (holding x.json), l.off and l.json (symbolic links to outside/in's
//!                             files), ld (to outside/in/dir), dangling.json (to the missing
//!                             outside/in/missing.json), loop.off (a link to itself).
//! Names may use "/", "..", ".", the links, "-" (standard output, which the target sends to
//! /dev/null) and the absolute names /dev/null and /dev/full (a device that fails every write).
//! An input with another absolute name or with more than two ".." components is skipped: nothing
//! else can reach above <root>/work, so the whole run stays inside <root>.
//!
//! Every output is added (OutputSet::add) and, if all were accepted, written with distinct
//! contents (OutputSet::write).  The findings:
//!  - an exception other than InvalidInput or OutputError;
//!  - two outputs accepted that name the same file (the same existing file by any name; for a
//!    new name, the same directory and name);
//!  - after a refusal (of a name, or of the writes): any change under <root>;
//!  - after the writes: any change under <root> other than the named files — each name's
//!    directory resolved, and a symbolic link as the last component followed to its target —, or
//!    a named file that does not hold exactly what its writer wrote (a temporary file left behind
//!    is such a change).

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <typeinfo>
#include <vector>

#include "apps/output_files.h"
#include "common/errors.h"

namespace {

namespace fs = std::filesystem;
using delmesh::app::OutputError;
using delmesh::app::OutputSet;

constexpr std::size_t max_outputs = 3;
const char* const option_names[max_outputs] = {"--out", "--stats", "--extra"};

std::string root;  // the mkdtemp directory
std::string work;  // <root>/work/a/b

void remove_root() {
  std::error_code ec;
  if (!root.empty()) fs::remove_all(root, ec);
}

[[noreturn]] void finding(const std::string& what) {
  std::fprintf(stderr, "fuzz: %s\n", what.c_str());
  std::abort();
}

void write_file(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
  if (!out) finding("cannot set up " + path);
}

//! Rebuilds the scratch tree of the file comment under <root>.
void set_up_tree() {
  std::error_code ec;
  for (const char* top : {"/outside", "/work"}) {
    fs::remove_all(root + top, ec);
    if (ec) finding("cannot clear " + root + top + ": " + ec.message());
  }
  const std::string in = root + "/outside/in";
  fs::create_directories(in + "/dir");
  fs::create_directories(work + "/d");
  write_file(in + "/o.off", "outside off\n");
  write_file(in + "/o.json", "outside json\n");
  write_file(in + "/dir/f.json", "outside dir json\n");
  write_file(work + "/a.off", "old off\n");
  write_file(work + "/a.json", "old json\n");
  write_file(work + "/d/x.json", "old d json\n");
  fs::create_hard_link(work + "/a.off", work + "/h.off");
  fs::create_symlink(in + "/o.off", work + "/l.off");
  fs::create_symlink("../../../outside/in/o.json", work + "/l.json");  // relative
  fs::create_directory_symlink(in + "/dir", work + "/ld");
  fs::create_symlink(in + "/missing.json", work + "/dangling.json");
  fs::create_symlink("loop.off", work + "/loop.off");
}

//! What a tree entry is: its type, and a file's contents or a link's target.
struct Entry {
  char type = '?';  // f file, d directory, l link, ? other
  std::string contents;
  bool operator==(const Entry& other) const { return type == other.type && contents == other.contents; }
};

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

//! Every entry under <root> by its path relative to <root>, links not followed.
std::map<std::string, Entry> snapshot() {
  std::map<std::string, Entry> entries;
  for (const auto& item : fs::recursive_directory_iterator(root)) {
    const std::string path = item.path().string();
    Entry entry;
    const fs::file_status status = item.symlink_status();
    if (fs::is_symlink(status)) {
      entry.type = 'l';
      entry.contents = fs::read_symlink(item.path()).string();
    } else if (fs::is_directory(status)) {
      entry.type = 'd';
    } else if (fs::is_regular_file(status)) {
      entry.type = 'f';
      entry.contents = read_file(path);
    }
    entries[path.substr(root.size())] = entry;
  }
  return entries;
}

//! The scratch tree's files that writing to `name` may create or replace, as absolute paths: the
//! name with its directory resolved and, while it is a symbolic link, followed.  Nothing for "-"
//! and the devices, or a name whose directory does not resolve.
std::optional<std::string> written_file(const std::string& name) {
  if (name == "-" || name.rfind("/dev/", 0) == 0) return std::nullopt;
  fs::path path = fs::path(work) / name;
  for (int hop = 0; hop < 40; ++hop) {
    std::error_code ec;
    const fs::path directory = fs::canonical(path.parent_path(), ec);
    if (ec) return std::nullopt;
    path = directory / path.filename();
    if (!fs::is_symlink(fs::symlink_status(path, ec))) return path.string();
    const fs::path target = fs::read_symlink(path, ec);
    if (ec) return std::nullopt;
    path = target.is_absolute() ? target : directory / target;
  }
  return std::nullopt;
}

//! The identity OutputSet::add compares: (device, inode) of an existing file, or of a new name's
//! directory with the name.
std::optional<std::tuple<dev_t, ino_t, std::string>> identity(const std::string& name) {
  struct stat status {};
  if (name == "-") {
    if (::fstat(STDOUT_FILENO, &status) != 0) return std::nullopt;
    return std::tuple{status.st_dev, status.st_ino, std::string()};
  }
  const std::string path = name.rfind("/dev/", 0) == 0 ? name : work + "/" + name;
  if (::stat(path.c_str(), &status) == 0) return std::tuple{status.st_dev, status.st_ino, std::string()};
  const std::optional<std::string> file = written_file(name);
  if (!file) return std::nullopt;
  const fs::path p(*file);
  if (::stat(p.parent_path().c_str(), &status) != 0) return std::nullopt;
  return std::tuple{status.st_dev, status.st_ino, p.filename().string()};
}

void report_changes(const std::map<std::string, Entry>& before, const std::map<std::string, Entry>& after,
                    const std::set<std::string>& allowed, const std::string& when) {
  std::set<std::string> paths;
  for (const auto& [path, entry] : before) paths.insert(path);
  for (const auto& [path, entry] : after) paths.insert(path);
  for (const std::string& path : paths) {
    const auto b = before.find(path), a = after.find(path);
    const bool same = b != before.end() && a != after.end() && b->second == a->second;
    if (!same && allowed.count(path) == 0)
      finding(when + ": " + path + (b == before.end() ? " appeared" : a == after.end() ? " vanished" : " changed") +
              " under the scratch directory");
  }
}

//! Makes the working directory the scratch one for its lifetime (libFuzzer's own relative paths
//! stay valid between inputs).
class InWorkDirectory {
 public:
  InWorkDirectory() : previous_(fs::current_path()) { change(work); }
  ~InWorkDirectory() { change(previous_.string()); }
  InWorkDirectory(const InWorkDirectory&) = delete;
  InWorkDirectory& operator=(const InWorkDirectory&) = delete;

 private:
  static void change(const std::string& directory) {
    if (::chdir(directory.c_str()) != 0) finding("chdir " + directory + " failed");
  }
  fs::path previous_;
};

//! Runs body(); returns true if it returned, false if it threw InvalidInput or OutputError; any
//! other exception is a finding.
template <class Body>
bool accepted(const std::string& what, Body&& body) {
  try {
    body();
    return true;
  } catch (const delmesh::InvalidInput&) {
    return false;
  } catch (const OutputError&) {
    return false;
  } catch (const std::exception& e) {
    finding(what + " threw " + typeid(e).name() + ": " + e.what());
  } catch (...) {
    finding(what + " threw a non-standard exception");
  }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  std::error_code ec;
  const fs::path base = fs::is_directory("/dev/shm", ec) ? fs::path("/dev/shm") : fs::temp_directory_path();
  std::string pattern = (base / "delmesh-fuzz-outputs-XXXXXX").string();
  if (!::mkdtemp(pattern.data())) finding("mkdtemp failed");
  root = pattern;
  work = root + "/work/a/b";
  std::atexit(remove_root);
  // Standard output ("-") goes to /dev/null: libFuzzer reports on standard error.
  const int null = ::open("/dev/null", O_WRONLY);
  if (null < 0 || ::dup2(null, STDOUT_FILENO) < 0) finding("cannot send standard output to /dev/null");
  ::close(null);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static std::uint64_t input_number = 0;
  ++input_number;
  std::vector<std::string> names;
  const std::string text(reinterpret_cast<const char*>(data), size);
  // One name per line; a final line break ends the last name rather than starting an empty one.
  const std::size_t length = !text.empty() && text.back() == '\n' ? text.size() - 1 : text.size();
  for (std::size_t at = 0; at <= length && names.size() < max_outputs;) {
    std::size_t end = text.find('\n', at);
    if (end == std::string::npos || end > length) end = length;
    names.push_back(text.substr(at, end - at));
    at = end + 1;
  }
  for (const std::string& name : names) {
    if (name.find('\0') != std::string::npos) return 0;
    if (!name.empty() && name[0] == '/' && name != "/dev/null" && name != "/dev/full") return 0;
    int up = 0;
    for (const fs::path& part : fs::path(name)) up += part == "..";
    if (up > 2) return 0;
  }

  set_up_tree();
  const std::map<std::string, Entry> before = snapshot();
  std::vector<std::string> contents;
  std::set<std::string> allowed;
  bool written = false;
  {
    InWorkDirectory in_work;
    OutputSet outputs;
    std::vector<std::optional<std::tuple<dev_t, ino_t, std::string>>> identities;
    bool all_added = true;
    for (std::size_t i = 0; i < names.size() && all_added; ++i) {
      const auto id = identity(names[i]);
      all_added = accepted("OutputSet::add", [&] { (void)outputs.add(option_names[i], names[i]); });
      if (!all_added) break;
      for (std::size_t j = 0; j < identities.size(); ++j)
        if (id && identities[j] && *id == *identities[j])
          finding("OutputSet::add accepted " + std::string(option_names[i]) + " '" + names[i] + "' and " +
                  option_names[j] + " '" + names[j] + "', the same file");
      identities.push_back(id);
    }
    if (all_added) {
      std::vector<OutputSet::Writer> writers;
      for (std::size_t i = 0; i < names.size(); ++i) {
        contents.push_back("output " + std::to_string(i) + " of input " + std::to_string(input_number) + "\n");
        writers.push_back([text = contents.back()](std::ostream& out) { out << text; });
      }
      written = accepted("OutputSet::write", [&] { outputs.write(writers); });
      if (written)
        for (const std::string& name : names)
          if (const auto file = written_file(name)) allowed.insert(file->substr(root.size()));
    }
  }
  const std::map<std::string, Entry> after = snapshot();
  report_changes(before, after, allowed, written ? "after OutputSet::write" : "after a refusal");
  if (written) {
    for (std::size_t i = 0; i < names.size(); ++i) {
      const auto file = written_file(names[i]);
      if (!file) continue;
      const auto entry = after.find(file->substr(root.size()));
      if (entry == after.end() || entry->second.type != 'f' || entry->second.contents != contents[i])
        finding(std::string(option_names[i]) + " '" + names[i] + "': " + *file + " does not hold what was written");
    }
  }
  return 0;
}
