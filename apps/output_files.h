#pragma once
//! \file output_files.h
//! The output files of one run of `delmesh`, written as a group: all of them or none.
//!
//! An output is named on the command line and is one of
//!  - "-": standard output, written in place;
//!  - an existing character or block device, FIFO or socket (after following symbolic links),
//!    e.g. /dev/null: written in place, never replaced;
//!  - a regular file, or a name that does not exist yet: written to a temporary file in the
//!    directory of the target and renamed over it.  A symbolic link (also one whose target does
//!    not exist yet) is followed, so its target is written and the link stays.
//!
//! OutputSet::write() writes every temporary file first, then every in-place output, and renames
//! the temporaries over their targets only after all of that succeeded: an output that cannot be
//! written (disk full, permission denied, a closed pipe) leaves every existing file as it was.
//! Before the renames, each file about to be replaced gets a second name (a hard link
//! `.<name>.old<pid>` beside it); if a rename fails after others succeeded (the directory changed
//! under the run), the replaced files are renamed back from those links and the new files that
//! had no predecessor are removed, so the group is still all or nothing.  Only a file that could
//! not be linked (a file system without hard links) cannot be put back; the message names it.
//! Temporary files are registered with apps/interrupt.h, so they are removed on every way out:
//! an exception, a second signal, std::terminate.  A second signal that arrives during the
//! renames ends the process only once they are all done.
//!
//! Concurrent runs: the renames of one group happen under an exclusive flock(2) on each target
//! directory (taken in the order of device and inode numbers, so two runs cannot deadlock).
//! Two runs that write the same outputs therefore leave the files of one run or of the other,
//! never a mix (on file systems where flock works; where it fails with an error other than
//! "would block", the renames go ahead without the lock).  A run waits at most
//! output_lock_wait_seconds for the lock, then fails with an OutputError and leaves every file
//! as it was.

#include <sys/types.h>

#include <cstddef>
#include <functional>
#include <iosfwd>
#include <stdexcept>
#include <string>
#include <vector>

namespace delmesh::app {

//! An output that cannot be written (disk full, permission denied, a closed pipe, a lock held
//! too long): the command line turns it into one line `error: <what()>` and exit code 6
//! (ExitCode::io_error).  Invalid names (a directory, a missing directory) are InvalidInput.
struct OutputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

//! The longest wait, in seconds, for another run's renames into the same directory.
inline constexpr double output_lock_wait_seconds = 5;

//! A group of outputs, checked when added and written together.
class OutputSet {
 public:
  //! Writes one output's bytes to the stream (a failed write shows in the stream's state).
  using Writer = std::function<void(std::ostream&)>;

  OutputSet() = default;
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;
  //! Removes the temporary files of a write() that did not finish.
  ~OutputSet();

  //! Adds the output `path`, given by the command-line option `option` (for messages), and
  //! returns its index.  Throws InvalidInput, with the option in the message, if the path is
  //! empty or a directory, its directory does not exist, a component is not a directory, or it
  //! is the same file as an output added before (same device and inode; for names that do not
  //! exist yet, the same directory and file name; "-" is the file of standard output).  Throws
  //! OutputError if the location is not writable (access(2)).
  std::size_t add(const std::string& option, const std::string& path);

  //! Writes output i with writers[i] and commits the group as the file comment says.  Throws
  //! OutputError (exit code 6) if an output cannot be written or renamed, and passes on what a
  //! writer throws; either way every existing file is left as it was (but for a file that could
  //! not be linked before the renames, which the message names).
  //! \pre writers.size() equals the number of outputs added, and write() was not called before.
  void write(const std::vector<Writer>& writers);

 private:
  enum class Kind { standard_output, in_place, replace };
  //! What stood at a replace output's target before the renames.
  enum class Previous { none, kept, not_kept };
  struct Output {
    std::string option, path;  // as given
    Kind kind = Kind::replace;
    std::string target;        // the file replaced: symbolic links followed, absolute
    std::string directory;     // the directory of target
    dev_t device = 0;          // identity: the file's, or for a new name its directory's
    ino_t inode = 0;
    std::string name;          // "" for an existing file; the file name for a new one
    bool identified = false;   // false: standard output is closed
    mode_t mode = 0666;        // the mode of the temporary file (the target's if it exists)
    std::string temporary;     // while written
    std::size_t slot = 0;      // its registration (apps/interrupt.h)
    Previous previous = Previous::none;
    std::string kept;          // the second name of the previous file while the group commits
    std::size_t kept_slot = 0;
  };
  void write_temporary(Output& output, const Writer& writer);
  void write_in_place(const Output& output, const Writer& writer);
  void commit();
  //! Gives the file at output.target a second name (Previous::kept), or records that there is no
  //! file (none) or that it could not be linked (not_kept).
  void keep_previous(Output& output);
  //! After the renames of outputs_[0, failed) succeeded and that of outputs_[failed] did not:
  //! puts the kept files back and removes the new ones; returns the targets it could not restore.
  std::string roll_back(std::size_t failed) noexcept;
  void discard(Output& output) noexcept;

  std::vector<Output> outputs_;
};

//! Makes std::cout write to file descriptor 1 through a buffer of its own that keeps the errno of
//! the first failed write, for finish_standard_output() to report.  Call it before anything is
//! written to std::cout (the program does, first thing in main).
void route_standard_output();

//! Flushes standard output and throws OutputError ("cannot write to standard output: …", with the
//! reason if route_standard_output() was called) if any write to it failed, e.g. a full disk
//! (/dev/full) or a closed pipe (EPIPE).
void finish_standard_output();

}  // namespace delmesh::app
