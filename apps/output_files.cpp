#include "apps/output_files.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <ostream>
#include <streambuf>
#include <thread>
#include <tuple>

#include "apps/interrupt.h"
#include "common/errors.h"

namespace delmesh::app {

namespace {

//! Symbolic links followed before a name is refused (the limit of the Linux kernel).
constexpr int max_link_hops = 40;

//! An open file descriptor, closed at the end of its scope.
class FileDescriptor {
 public:
  explicit FileDescriptor(int fd = -1) : fd_(fd) {}
  ~FileDescriptor() { reset(); }
  FileDescriptor(FileDescriptor&& other) noexcept : fd_(other.release()) {}
  FileDescriptor& operator=(FileDescriptor&& other) noexcept {
    if (this != &other) {
      reset();
      fd_ = other.release();
    }
    return *this;
  }
  int get() const { return fd_; }
  int release() {
    const int fd = fd_;
    fd_ = -1;
    return fd;
  }
  //! Closes the descriptor; returns close(2)'s errno, 0 on success.
  int close() {
    if (fd_ < 0) return 0;
    const int result = ::close(release());
    return result == 0 ? 0 : errno;
  }

 private:
  void reset() {
    if (fd_ >= 0) ::close(release());
  }
  int fd_;
};

//! A stream buffer over a file descriptor that keeps the errno of the first failed write(2).
class FdBuffer : public std::streambuf {
 public:
  explicit FdBuffer(int fd) : fd_(fd) { setp(buffer_, buffer_ + sizeof buffer_); }
  //! The errno of the first failed write, 0 if none failed.
  int error() const { return error_; }

 protected:
  int_type overflow(int_type c) override {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  int sync() override { return drain() ? 0 : -1; }

 private:
  bool drain() {
    if (error_ != 0) return false;
    const char* data = pbase();
    std::size_t left = static_cast<std::size_t>(pptr() - pbase());
    while (left > 0) {
      const ssize_t written = ::write(fd_, data, left);
      if (written < 0 && errno == EINTR) continue;
      if (written <= 0) {
        error_ = written < 0 ? errno : EIO;
        return false;
      }
      data += written;
      left -= static_cast<std::size_t>(written);
    }
    setp(buffer_, buffer_ + sizeof buffer_);
    return true;
  }
  int fd_;
  int error_ = 0;
  char buffer_[1 << 16];
};

//! Writes with `writer` to the open file `fd`, flushes, and closes it; returns the errno of the
//! first failure (a write, or close(2)), 0 if none.  A writer's exception passes through.
int write_to(FileDescriptor& fd, const OutputSet::Writer& writer) {
  FdBuffer buffer(fd.get());
  std::ostream stream(&buffer);
  writer(stream);
  stream.flush();
  int error = buffer.error();
  if (error == 0 && !stream.good()) error = EIO;
  const int close_error = fd.close();
  return error != 0 ? error : close_error;
}

std::string parent_of(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  if (slash == 0) return "/";
  return path.substr(0, slash);
}

std::string name_of(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

//! The canonical absolute form of an existing path (realpath(3)), or "" with errno set.
std::string canonical(const std::string& path) {
  char resolved[PATH_MAX];
  if (::realpath(path.c_str(), resolved) == nullptr) return {};
  return resolved;
}

//! `path` with its symbolic links followed as long as the name is one, also to a target that does
//! not exist: the name that writing through `path` creates or replaces.
std::string follow_links(const std::string& option, const std::string& path) {
  std::string current = path;
  for (int hop = 0; hop < max_link_hops; ++hop) {
    struct stat link {};
    if (::lstat(current.c_str(), &link) != 0 || !S_ISLNK(link.st_mode)) return current;
    std::string target(static_cast<std::size_t>(PATH_MAX), '\0');
    const ssize_t length = ::readlink(current.c_str(), target.data(), target.size());
    if (length < 0 || static_cast<std::size_t>(length) >= target.size())
      throw OutputError(option + ": cannot read the symbolic link " + current);
    target.resize(static_cast<std::size_t>(length));
    current = !target.empty() && target[0] == '/' ? target : parent_of(current) + "/" + target;
  }
  throw InvalidInput(option + ": " + path + ": too many levels of symbolic links");
}

std::string errno_text(int error) { return std::strerror(error); }

}  // namespace

OutputSet::~OutputSet() {
  for (Output& output : outputs_) discard(output);
}

void OutputSet::discard(Output& output) noexcept {
  if (!output.kept.empty()) {
    ::unlink(output.kept.c_str());
    unregister_temporary(output.kept_slot);
    output.kept.clear();
  }
  if (output.temporary.empty()) return;
  ::unlink(output.temporary.c_str());
  unregister_temporary(output.slot);
  output.temporary.clear();
}

void OutputSet::keep_previous(Output& output) {
  const std::string base =
      output.directory + (output.directory == "/" ? "" : "/") + "." + name_of(output.target) + ".old" +
      std::to_string(::getpid());
  output.previous = Previous::not_kept;
  for (int attempt = 0; attempt <= 100; ++attempt) {
    const std::string candidate = attempt == 0 ? base : base + "-" + std::to_string(attempt);
    std::size_t slot = 0;
    try {
      slot = register_temporary(candidate);
    } catch (const std::length_error&) {
      return;
    }
    if (::link(output.target.c_str(), candidate.c_str()) == 0) {
      output.previous = Previous::kept;
      output.kept = candidate;
      output.kept_slot = slot;
      return;
    }
    const int error = errno;
    unregister_temporary(slot);
    if (error == ENOENT) {
      output.previous = Previous::none;
      return;
    }
    if (error != EEXIST) return;
  }
}

std::string OutputSet::roll_back(std::size_t failed) noexcept {
  std::string lost;
  for (std::size_t i = failed; i-- > 0;) {
    Output& output = outputs_[i];
    if (output.kind != Kind::replace) continue;
    bool restored = false;
    if (output.previous == Previous::kept) {
      restored = ::rename(output.kept.c_str(), output.target.c_str()) == 0;
      if (restored) {
        unregister_temporary(output.kept_slot);
        output.kept.clear();
      }
    } else if (output.previous == Previous::none) {
      restored = ::unlink(output.target.c_str()) == 0;
    }
    if (restored) continue;
    lost += (lost.empty() ? "" : ", ") + output.path;
    if (!output.kept.empty()) {
      // Left on disk: now the only name of the previous file.
      lost += " (its previous content is in " + output.kept + ")";
      unregister_temporary(output.kept_slot);
      output.kept.clear();
    }
  }
  return lost;
}

std::size_t OutputSet::add(const std::string& option, const std::string& path) {
  if (path.empty()) throw InvalidInput(option + ": empty file name");
  Output output;
  output.option = option;
  output.path = path;
  struct stat status {};
  if (path == "-") {
    output.kind = Kind::standard_output;
    if (::fstat(STDOUT_FILENO, &status) == 0) {
      output.device = status.st_dev;
      output.inode = status.st_ino;
      output.identified = true;
    }
  } else if (::stat(path.c_str(), &status) == 0) {
    if (S_ISDIR(status.st_mode)) throw InvalidInput(option + ": " + path + " is a directory");
    output.device = status.st_dev;
    output.inode = status.st_ino;
    output.identified = true;
    if (S_ISREG(status.st_mode)) {
      output.kind = Kind::replace;
      output.target = canonical(path);
      if (output.target.empty()) throw OutputError(option + ": cannot resolve " + path + ": " + errno_text(errno));
      output.directory = parent_of(output.target);
      output.mode = status.st_mode & 07777;
    } else {
      output.kind = Kind::in_place;
      if (::access(path.c_str(), W_OK) != 0)
        throw OutputError(option + ": cannot write " + path + ": " + errno_text(errno));
    }
  } else {
    const int error = errno;
    if (error == ENOTDIR) throw InvalidInput(option + ": a component of " + path + " is not a directory");
    if (error == ELOOP) throw InvalidInput(option + ": " + path + ": too many levels of symbolic links");
    if (error != ENOENT) throw OutputError(option + ": cannot write " + path + ": " + errno_text(error));
    // A new name, perhaps reached through a symbolic link whose target does not exist yet.
    const std::string name_path = follow_links(option, path);
    const std::string name = name_of(name_path);
    if (name.empty() || name == "." || name == "..") throw InvalidInput(option + ": " + path + " is a directory");
    const std::string directory = parent_of(name_path);
    struct stat directory_status {};
    if (::stat(directory.c_str(), &directory_status) != 0 || !S_ISDIR(directory_status.st_mode))
      throw InvalidInput(option + ": directory " + directory + " does not exist");
    output.kind = Kind::replace;
    output.directory = canonical(directory);
    if (output.directory.empty())
      throw OutputError(option + ": cannot resolve directory " + directory + ": " + errno_text(errno));
    output.target = (output.directory == "/" ? "" : output.directory) + "/" + name;
    output.device = directory_status.st_dev;
    output.inode = directory_status.st_ino;
    output.name = name;
    output.identified = true;
  }
  if (output.kind == Kind::replace && ::access(output.directory.c_str(), W_OK | X_OK) != 0)
    throw OutputError(option + ": directory " + parent_of(path) + " is not writable: " + errno_text(errno));
  for (const Output& before : outputs_) {
    if (before.identified && output.identified && before.device == output.device && before.inode == output.inode &&
        before.name == output.name)
      throw InvalidInput(output.option + " and " + before.option + " name the same file (" + output.path +
                         (output.path == before.path ? "" : " and " + before.path) + ")");
  }
  outputs_.push_back(std::move(output));
  return outputs_.size() - 1;
}

void OutputSet::write(const std::vector<Writer>& writers) {
  if (writers.size() != outputs_.size())
    throw PreconditionViolation("OutputSet::write: one writer per output is needed");
  for (std::size_t i = 0; i < outputs_.size(); ++i)
    if (outputs_[i].kind == Kind::replace) write_temporary(outputs_[i], writers[i]);
  for (std::size_t i = 0; i < outputs_.size(); ++i)
    if (outputs_[i].kind != Kind::replace) write_in_place(outputs_[i], writers[i]);
  commit();
}

void OutputSet::write_temporary(Output& output, const Writer& writer) {
  const std::string base =
      output.directory + (output.directory == "/" ? "" : "/") + "." + name_of(output.target) + ".tmp" +
      std::to_string(::getpid());
  FileDescriptor fd;
  for (int attempt = 0; fd.get() < 0; ++attempt) {
    const std::string candidate = attempt == 0 ? base : base + "-" + std::to_string(attempt);
    // Registered before it exists, so that no moment leaves it unregistered.
    std::size_t slot = 0;
    try {
      slot = register_temporary(candidate);
    } catch (const std::length_error& e) {
      throw OutputError(output.option + ": cannot write " + output.path + ": " + e.what());
    }
    fd = FileDescriptor(::open(candidate.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666));
    if (fd.get() >= 0) {
      output.temporary = candidate;
      output.slot = slot;
      break;
    }
    const int error = errno;
    unregister_temporary(slot);
    if (error != EEXIST || attempt >= 100)
      throw OutputError(output.option + ": cannot write " + output.path + ": " + errno_text(error));
  }
  if (output.identified && output.name.empty()) {
    // Replacing a file keeps its permissions (and, where allowed, its owner).
    struct stat status {};
    if (::stat(output.target.c_str(), &status) == 0) {
      (void)::fchown(fd.get(), status.st_uid, status.st_gid);
      (void)::fchmod(fd.get(), status.st_mode & 07777);
    }
  }
  const int error = write_to(fd, writer);
  if (error != 0) throw OutputError(output.option + ": cannot write " + output.path + ": " + errno_text(error));
}

void OutputSet::write_in_place(const Output& output, const Writer& writer) {
  if (output.kind == Kind::standard_output) {
    writer(std::cout);
    try {
      finish_standard_output();
    } catch (const OutputError& e) {
      throw OutputError(output.option + ": " + e.what());
    }
    return;
  }
  FileDescriptor fd(::open(output.path.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC));
  if (fd.get() < 0) throw OutputError(output.option + ": cannot write " + output.path + ": " + errno_text(errno));
  const int error = write_to(fd, writer);
  if (error != 0) throw OutputError(output.option + ": cannot write " + output.path + ": " + errno_text(error));
}

void OutputSet::commit() {
  // The target directories, each opened once, in the order of (device, inode).
  struct Directory {
    dev_t device;
    ino_t inode;
    std::string path;
    FileDescriptor fd;
  };
  std::vector<Directory> directories;
  for (const Output& output : outputs_) {
    if (output.kind != Kind::replace) continue;
    FileDescriptor fd(::open(output.directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
    struct stat status {};
    if (fd.get() < 0 || ::fstat(fd.get(), &status) != 0) continue;  // unlockable: renamed without the lock
    const bool known = std::any_of(directories.begin(), directories.end(), [&](const Directory& d) {
      return d.device == status.st_dev && d.inode == status.st_ino;
    });
    if (!known) directories.push_back({status.st_dev, status.st_ino, output.directory, std::move(fd)});
  }
  std::sort(directories.begin(), directories.end(), [](const Directory& a, const Directory& b) {
    return std::tie(a.device, a.inode) < std::tie(b.device, b.inode);
  });
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::duration<double>(output_lock_wait_seconds);
  for (Directory& directory : directories) {
    while (::flock(directory.fd.get(), LOCK_EX | LOCK_NB) != 0) {
      if (errno == EINTR) continue;
      if (errno != EWOULDBLOCK) break;  // no locks on this file system
      if (std::chrono::steady_clock::now() > give_up)
        throw OutputError("another process has been replacing files in " + directory.path + " for " +
                          std::to_string(static_cast<int>(output_lock_wait_seconds)) +
                          " s (it holds flock(2) on the directory); no output was replaced");
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }
  DeferredExit renames_first;
  for (Output& output : outputs_)
    if (!output.temporary.empty()) keep_previous(output);
  for (std::size_t i = 0; i < outputs_.size(); ++i) {
    Output& output = outputs_[i];
    if (output.temporary.empty()) continue;
    if (::rename(output.temporary.c_str(), output.target.c_str()) != 0) {
      const int error = errno;
      const std::string lost = roll_back(i);
      throw OutputError(output.option + ": cannot replace " + output.path + ": " + errno_text(error) +
                        (lost.empty() ? std::string() : " (" + lost + " was already replaced and could not be restored)"));
    }
    unregister_temporary(output.slot);
    output.temporary.clear();
  }
  // The previous files' second names go; the locks go with `directories`, after the renames.
  for (Output& output : outputs_) discard(output);
}

namespace {

//! The buffer of std::cout after route_standard_output(); never destroyed, since std::cout is
//! flushed at exit after static objects are gone.
FdBuffer* standard_output_buffer = nullptr;

}  // namespace

void route_standard_output() {
  if (standard_output_buffer != nullptr) return;
  std::cout.flush();
  standard_output_buffer = new FdBuffer(STDOUT_FILENO);
  std::cout.rdbuf(standard_output_buffer);
}

void finish_standard_output() {
  errno = 0;
  std::cout.flush();
  int error = standard_output_buffer != nullptr ? standard_output_buffer->error() : errno;
  bool failed = !std::cout.good() || error != 0;
  if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
    failed = true;
    if (error == 0) error = errno;
  }
  if (!failed) return;
  throw OutputError("cannot write to standard output: " +
                    (error != 0 ? errno_text(error) : std::string("the write failed")));
}

}  // namespace delmesh::app
