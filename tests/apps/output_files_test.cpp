// Tests of apps/output_files.h through the program: devices, FIFOs and links as outputs, outputs
// that are the same file, a failing output that must leave every file as it was, errors on
// standard output (exit code 6), and concurrent runs writing the same pair of files.
#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include <boost/test/unit_test.hpp>
#include <nlohmann/json.hpp>

#include "meshing/inputs/mesh_io.h"
#include "run_delmesh.h"

using namespace delmesh;
using namespace delmesh::test;
namespace fs = std::filesystem;

namespace {

const std::string old_mesh = "OLD MESH\n", old_stats = "OLD STATISTICS\n";

// Makes a character device node with the numbers of /dev/null (1, 3) or /dev/full (1, 7) at
// `path`, so that the tests never name the machine's own devices as outputs.  False (with a
// message) if the test does not run as root or the node cannot be made.
bool make_device(const fs::path& path, unsigned minor) {
  if (::geteuid() != 0) {
    BOOST_TEST_MESSAGE("skipped: making a device node needs root");
    return false;
  }
  if (::mknod(path.c_str(), S_IFCHR | 0666, makedev(1, minor)) != 0) {
    BOOST_TEST_MESSAGE("skipped: mknod " << path << " failed: " << std::strerror(errno));
    return false;
  }
  return ::chmod(path.c_str(), 0666) == 0;  // writable by everyone, as the real devices are
}

// Whether `path` is still the character device (1, minor).
bool is_device(const fs::path& path, unsigned minor) {
  struct stat status {};
  return ::lstat(path.c_str(), &status) == 0 && S_ISCHR(status.st_mode) && major(status.st_rdev) == 1 &&
         ::minor(status.st_rdev) == minor;
}

// The mesh file and the statistics (JSON text) are of the same run: the vertex and triangle
// counts of the file are those the statistics give.
void check_pair(const fs::path& mesh, const std::string& statistics_text) {
  const auto statistics = nlohmann::json::parse(statistics_text);
  const TriangleSoup soup = read_triangle_soup(mesh.string());
  BOOST_TEST(soup.points.size() == statistics.at("vertices").get<std::size_t>());
  BOOST_TEST(soup.triangles.size() == statistics.at("triangles").get<std::size_t>());
}

// Reads everything from the file descriptor `fd` (on a thread of the caller) and closes it.
std::string read_all(int fd) {
  std::string text;
  char buffer[4096];
  for (ssize_t n; (n = ::read(fd, buffer, sizeof buffer)) != 0;) {
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) break;
    text.append(buffer, static_cast<std::size_t>(n));
  }
  ::close(fd);
  return text;
}

const std::vector<std::string> sphere{"mesh", "--surface", "sphere", "--quiet"};

std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& more) {
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(output_files)

// A device node given as --stats or --out is written in place: it stays a device (a regular file
// renamed over it would replace it), and the run succeeds.
BOOST_AUTO_TEST_CASE(devices_are_written_in_place) {
  TempDir dir;
  if (!make_device(dir / "null", 3) || !make_device(dir / "null.off", 3)) return;
  fs::create_directory(dir / "o");
  RunResult r = run_delmesh(with(sphere, {"--out", "o/m.off", "--stats", "null"}), dir.path);
  BOOST_TEST(r.exit_code == 0, r.err);
  BOOST_TEST(is_device(dir / "null", 3));
  BOOST_TEST(read_triangle_soup((dir / "o/m.off").string()).triangles.size() > 0u);
  r = run_delmesh(with(sphere, {"--out", "null.off", "--stats", "s.json"}), dir.path);
  BOOST_TEST(r.exit_code == 0, r.err);
  BOOST_TEST(is_device(dir / "null.off", 3));
  BOOST_TEST(nlohmann::json::parse(read_text(dir / "s.json"))["status"] == "complete");
  BOOST_TEST(temporaries_in(dir.path).empty());
}

// A user who may write a device but not its directory writes it in place: nothing needs to be
// created next to it.  (The program runs as nobody, uid 65534.)
BOOST_AUTO_TEST_CASE(a_device_needs_no_writable_directory) {
  TempDir dir;
  if (!make_device(dir / "null", 3)) return;
  // The run's working directory o/ may be written by anyone; the directory of the device may not.
  fs::create_directory(dir / "o");
  fs::permissions(dir / "o", fs::perms::all);
  fs::permissions(dir.path, fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                                fs::perms::others_read | fs::perms::others_exec);
  const uid_t nobody = 65534;
  const pid_t pid = spawn_delmesh(with(sphere, {"--out", "m.off", "--stats", "../null"}), dir / "o", -1, nobody);
  const RunResult r = wait_delmesh(pid, dir / "o");
  BOOST_TEST(r.exit_code == 0, r.err);
  BOOST_TEST(is_device(dir / "null", 3));
  BOOST_TEST(read_triangle_soup((dir / "o/m.off").string()).triangles.size() > 0u);
}

// A FIFO, and a symbolic link to the program's own standard output (a pipe), are written in
// place: the reader gets the statistics, the FIFO and the link stay what they were.
BOOST_AUTO_TEST_CASE(fifos_and_pipes_are_written_in_place) {
  TempDir dir;
  BOOST_TEST_REQUIRE(::mkfifo((dir / "fifo.json").c_str(), 0644) == 0);
  std::string from_fifo;
  std::thread reader([&] { from_fifo = read_all(::open((dir / "fifo.json").c_str(), O_RDONLY)); });
  RunResult r = run_delmesh(with(sphere, {"--out", "m.off", "--stats", "fifo.json"}), dir.path);
  // Releases a reader still waiting for a writer (if the run failed before opening the FIFO).
  if (const int writer = ::open((dir / "fifo.json").c_str(), O_WRONLY | O_NONBLOCK); writer >= 0) ::close(writer);
  reader.join();
  BOOST_TEST(r.exit_code == 0, r.err);
  BOOST_TEST(fs::is_fifo(dir / "fifo.json"));
  check_pair(dir / "m.off", from_fifo);

  fs::create_symlink("/proc/self/fd/1", dir / "stdout.json");
  int pipe_fds[2];
  BOOST_TEST_REQUIRE(::pipe(pipe_fds) == 0);
  const pid_t pid = spawn_delmesh(with(sphere, {"--out", "n.off", "--stats", "stdout.json"}), dir.path, pipe_fds[1]);
  ::close(pipe_fds[1]);
  const std::string from_pipe = read_all(pipe_fds[0]);
  r = wait_delmesh(pid, dir.path);
  BOOST_TEST(r.exit_code == 0, r.err);
  BOOST_TEST(fs::is_symlink(dir / "stdout.json"));
  check_pair(dir / "n.off", from_pipe);
  BOOST_TEST(temporaries_in(dir.path).empty());
}

// A symbolic link as output is followed: its target is replaced (or created, for a link whose
// target does not exist yet) and the link stays a link.
BOOST_AUTO_TEST_CASE(symbolic_links_are_followed) {
  TempDir dir;
  write_text(dir / "real.off", old_mesh);
  fs::create_symlink("real.off", dir / "link.off");
  fs::create_directory(dir / "d");
  fs::create_symlink("d/new.json", dir / "link.json");  // dangling until the run
  const RunResult r = run_delmesh(with(sphere, {"--out", "link.off", "--stats", "link.json"}), dir.path);
  BOOST_TEST(r.exit_code == 0, r.err);
  BOOST_TEST(fs::is_symlink(dir / "link.off"));
  BOOST_TEST(fs::read_symlink(dir / "link.off") == "real.off");
  BOOST_TEST(fs::is_symlink(dir / "link.json"));
  BOOST_TEST(fs::is_regular_file(dir / "d/new.json"));
  check_pair(dir / "real.off", read_text(dir / "d/new.json"));
  BOOST_TEST(temporaries_in(dir.path).empty());
}

// Two outputs that are the same file are refused before anything is written, however the names
// differ: through "..", a hard link, a symbolic link (also to a name that does not exist yet), or
// "-" when standard output is that file.
BOOST_AUTO_TEST_CASE(outputs_that_are_the_same_file_are_refused) {
  TempDir dir;
  fs::create_directory(dir / "o");
  write_text(dir / "o/x.off", old_mesh);
  fs::create_hard_link(dir / "o/x.off", dir / "o/hard.json");
  fs::create_symlink("x.off", dir / "o/soft.json");
  fs::create_symlink("new.off", dir / "o/dangling.json");
  const std::vector<std::vector<std::string>> pairs{
      {"--out", "o/x.off", "--stats", "o/../o/x.off"},       // an existing file through ".."
      {"--out", "o/y.off", "--stats", "o/../o/y.off"},       // a new name through ".."
      {"--out", "o/x.off", "--stats", "o/hard.json"},        // a hard link
      {"--out", "o/x.off", "--stats", "o/soft.json"},        // a symbolic link
      {"--out", "o/new.off", "--stats", "o/dangling.json"},  // a link to the same new name
  };
  for (const auto& pair : pairs) {
    const RunResult r = run_delmesh(with(sphere, pair), dir.path);
    BOOST_TEST_CONTEXT(pair[1] << " and " << pair[3]) { require_invalid_input(r, "name the same file"); }
  }
  BOOST_TEST(read_text(dir / "o/x.off") == old_mesh);
  BOOST_TEST(!fs::exists(dir / "o/y.off"));
  BOOST_TEST(!fs::exists(dir / "o/new.off"));

  // Standard output redirected to the --out file.
  const int fd = ::open((dir / "o/x.off").c_str(), O_WRONLY | O_APPEND);
  BOOST_TEST_REQUIRE(fd >= 0);
  const pid_t pid = spawn_delmesh(with(sphere, {"--out", "o/x.off", "--stats", "-"}), dir.path, fd);
  ::close(fd);
  require_invalid_input(wait_delmesh(pid, dir.path), "name the same file");
  BOOST_TEST(read_text(dir / "o/x.off") == old_mesh);
  BOOST_TEST(temporaries_in(dir / "o").empty());
}

// An output that cannot be written is an I/O error (exit code 6, one `error:` line that names the
// option and the reason), and the other output, written successfully before, does not replace
// its old file: the old mesh is still there, and no temporary file is left.
BOOST_AUTO_TEST_CASE(a_failing_output_leaves_every_file_untouched) {
  TempDir dir;
  write_text(dir / "k.off", old_mesh);
  write_text(dir / "k.json", old_stats);
  const auto check_untouched = [&](const RunResult& r, const std::string& reason) {
    BOOST_TEST(!r.signalled);
    BOOST_TEST(r.exit_code == 6, r.err);
    BOOST_TEST(r.single_error_line(), r.err);
    BOOST_TEST(r.err.find(reason) != std::string::npos, r.err);
    BOOST_TEST(read_text(dir / "k.off") == old_mesh);
    BOOST_TEST(read_text(dir / "k.json") == old_stats);
    BOOST_TEST(temporaries_in(dir.path).empty());
  };
  if (fs::is_directory("/sys/kernel")) {
    // A directory where no file can be created (sysfs), even by root.
    check_untouched(run_delmesh(with(sphere, {"--out", "k.off", "--stats", "/sys/kernel/x.json"}), dir.path),
                    "--stats");
  }
  // The statistics go to standard output, and standard output is full.
  const int full = ::open("/dev/full", O_WRONLY);
  if (full >= 0) {
    const pid_t pid = spawn_delmesh(with(sphere, {"--out", "k.off", "--stats", "-"}), dir.path, full);
    ::close(full);
    check_untouched(wait_delmesh(pid, dir.path), "No space left on device");
  }
  // A device that is always full, as --stats.
  if (make_device(dir / "full.json", 7)) {
    check_untouched(run_delmesh(with(sphere, {"--out", "k.off", "--stats", "full.json"}), dir.path),
                    "--stats: cannot write full.json: No space left on device");
    BOOST_TEST(is_device(dir / "full.json", 7));
  }
}

// A rename that fails after another one succeeded (here the statistics' name became a directory
// while the run was meshing) puts the replaced mesh back: the group stays all or nothing, and no
// temporary file or second name of the old file is left.
BOOST_AUTO_TEST_CASE(a_failed_rename_puts_the_replaced_files_back) {
  TempDir dir;
  write_text(dir / "k.off", old_mesh);
  const pid_t pid = spawn_delmesh({"mesh", "--surface", "torus", "--size-bound", "0.01", "--time-limit", "4", "--out",
                                   "k.off", "--stats", "new.json"},
                                  dir.path);
  // The outputs are checked before meshing starts, and the first progress line says it has.
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (read_text(dir / ".spawn.stderr").find("delmesh: meshing") == std::string::npos &&
         std::chrono::steady_clock::now() < give_up)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  fs::create_directory(dir / "new.json");
  write_text(dir / "new.json" / "inside", "a directory cannot be replaced by a file\n");
  const RunResult r = wait_delmesh(pid, dir.path);
  BOOST_TEST(!r.signalled);
  BOOST_TEST(r.exit_code == 6, r.err);
  BOOST_TEST(r.err.find("--stats: cannot replace new.json") != std::string::npos, r.err);
  BOOST_TEST(r.err.find("could not be restored") == std::string::npos, r.err);
  BOOST_TEST(read_text(dir / "k.off") == old_mesh);
  BOOST_TEST(temporaries_in(dir.path).empty());
  for (const auto& entry : fs::directory_iterator(dir.path))
    BOOST_TEST(entry.path().filename().string().find(".old") == std::string::npos, entry.path());
}

// Whatever a subcommand prints, a standard output that cannot take it (a full device, a closed
// pipe) gives exit code 6 and one `error:` line, never exit code 0 or death by SIGPIPE.
BOOST_AUTO_TEST_CASE(standard_output_errors_are_io_errors) {
  TempDir dir;
  write_text(dir / "oct.off", octahedron_off);
  const std::vector<std::vector<std::string>> commands{
      {"surfaces"},
      {"surfaces", "--json"},
      {"check", "oct.off"},
      {"check", "oct.off", "--json"},
      {"solve", "--surface", "sphere", "--primitive", "surface_critical", "--direction", "0,0,1"},
      with(sphere, {"--out", "m.off", "--stats", "-"}),
      {"--help"},
  };
  for (const auto& args : commands) {
    BOOST_TEST_CONTEXT(args[0] << " " << (args.size() > 1 ? args[1] : "")) {
      const int full = ::open("/dev/full", O_WRONLY);
      BOOST_TEST_REQUIRE(full >= 0);
      pid_t pid = spawn_delmesh(args, dir.path, full);
      ::close(full);
      RunResult r = wait_delmesh(pid, dir.path);
      BOOST_TEST(!r.signalled);
      BOOST_TEST(r.exit_code == 6, r.err);
      BOOST_TEST(r.single_error_line(), r.err);
      BOOST_TEST(r.err.find("standard output: No space left on device") != std::string::npos, r.err);

      int pipe_fds[2];
      BOOST_TEST_REQUIRE(::pipe(pipe_fds) == 0);
      ::close(pipe_fds[0]);
      pid = spawn_delmesh(args, dir.path, pipe_fds[1]);
      ::close(pipe_fds[1]);
      r = wait_delmesh(pid, dir.path);
      BOOST_TEST(!r.signalled);
      BOOST_TEST(r.exit_code == 6, r.err);
      BOOST_TEST(r.single_error_line(), r.err);
      BOOST_TEST(r.err.find("standard output: Broken pipe") != std::string::npos, r.err);
    }
  }
  BOOST_TEST(!fs::exists(dir / "m.off"));
}

// Two runs at once writing the same --out and --stats: the pair left is always one run's (the
// statistics name the seed, and each seed gives a mesh of its own size).
BOOST_AUTO_TEST_CASE(concurrent_runs_leave_one_runs_pair) {
  TempDir dir;
  const std::vector<std::string> seeds{"1", "2"};
  std::map<std::uint64_t, std::size_t> vertices;  // of each seed's mesh, run alone
  for (const std::string& seed : seeds) {
    const RunResult r = run_delmesh(with(sphere, {"--seed", seed, "--out", "m.off", "--stats", "m.json"}), dir.path);
    BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
    vertices[std::stoull(seed)] = read_triangle_soup((dir / "m.off").string()).points.size();
  }
  BOOST_TEST_REQUIRE(vertices[1] != vertices[2], "the two seeds must give meshes of different sizes");
  for (int pair = 0; pair < 10; ++pair) {
    fs::create_directory(dir / "a");
    fs::create_directory(dir / "b");
    const pid_t a = spawn_delmesh(with(sphere, {"--seed", "1", "--out", "../m.off", "--stats", "../m.json"}), dir / "a");
    const pid_t b = spawn_delmesh(with(sphere, {"--seed", "2", "--out", "../m.off", "--stats", "../m.json"}), dir / "b");
    const RunResult ra = wait_delmesh(a, dir / "a"), rb = wait_delmesh(b, dir / "b");
    BOOST_TEST(ra.exit_code == 0, ra.err);
    BOOST_TEST(rb.exit_code == 0, rb.err);
    const auto statistics = nlohmann::json::parse(read_text(dir / "m.json"));
    const std::size_t written = read_triangle_soup((dir / "m.off").string()).points.size();
    BOOST_TEST(written == vertices[statistics.at("seed").get<std::uint64_t>()], "pair " << pair);
    BOOST_TEST(written == statistics.at("vertices").get<std::size_t>(), "pair " << pair);
  }
  BOOST_TEST(temporaries_in(dir.path).empty());
}

// The renames wait for another holder of the directory's lock: while this test holds flock on the
// directory, the run has written its temporary files but replaced nothing; once the lock is
// released it replaces both files.  A lock held longer than output_lock_wait_seconds (5 s) makes
// the run fail with exit code 6, leaving the old files and no temporary.
BOOST_AUTO_TEST_CASE(renames_wait_for_the_directory_lock) {
  TempDir dir;
  const auto reset = [&] {
    write_text(dir / "m.off", old_mesh);
    write_text(dir / "m.json", old_stats);
  };
  const auto wait_for_temporaries = [&](pid_t pid) {
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (temporaries_in(dir.path).size() < 2 && std::chrono::steady_clock::now() < give_up)
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    siginfo_t info{};
    BOOST_TEST(::waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOHANG | WNOWAIT) == 0);
    BOOST_TEST(info.si_pid == 0, "the run ended while the directory was locked");
    BOOST_TEST(temporaries_in(dir.path).size() == 2u);
    BOOST_TEST(read_text(dir / "m.off") == old_mesh);
    BOOST_TEST(read_text(dir / "m.json") == old_stats);
  };
  const std::vector<std::string> args = with(sphere, {"--out", "m.off", "--stats", "m.json"});

  reset();
  int lock = ::open(dir.path.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  BOOST_TEST_REQUIRE(::flock(lock, LOCK_EX) == 0);
  pid_t pid = spawn_delmesh(args, dir.path);
  wait_for_temporaries(pid);
  ::close(lock);
  RunResult r = wait_delmesh(pid, dir.path);
  BOOST_TEST(r.exit_code == 0, r.err);
  check_pair(dir / "m.off", read_text(dir / "m.json"));
  BOOST_TEST(temporaries_in(dir.path).empty());

  reset();
  lock = ::open(dir.path.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  BOOST_TEST_REQUIRE(::flock(lock, LOCK_EX) == 0);
  pid = spawn_delmesh(args, dir.path);
  wait_for_temporaries(pid);
  r = wait_delmesh(pid, dir.path);
  ::close(lock);
  BOOST_TEST(r.exit_code == 6, r.err);
  BOOST_TEST(r.single_error_line(), r.err);
  BOOST_TEST(r.err.find("flock") != std::string::npos, r.err);
  BOOST_TEST(read_text(dir / "m.off") == old_mesh);
  BOOST_TEST(read_text(dir / "m.json") == old_stats);
  BOOST_TEST(temporaries_in(dir.path).empty());
}

BOOST_AUTO_TEST_SUITE_END()
