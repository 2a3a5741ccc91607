// Output files that are either complete or absent. Data go to a temporary
// file beside the target, created under an unpredictable name with O_EXCL
// (mkstemp: never an existing file, never through a link), and are moved
// onto the target only when complete; a temporary never committed is
// removed, by the destructor or, after install_signal_cleanup(), when
// SIGINT, SIGTERM or SIGHUP ends the program.
#pragma once

#include <string>
#include <string_view>

#include <sys/types.h>

namespace sol::programs {

class OutputFile {
 public:
  /// Creates the temporary beside `target`. Throws std::runtime_error naming
  /// the target when the target is a directory or its directory cannot take
  /// a new file.
  explicit OutputFile(std::string target);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  const std::string& target() const { return m_target; }
  /// The temporary to write to (until commit()), for writers that open
  /// files themselves; those that encode into memory use write().
  const std::string& path() const { return m_temporary; }
  /// Writes `bytes` to the temporary (replacing what it held), every write
  /// checked. Throws std::runtime_error naming the target and the reason
  /// (a full disk: "No space left on device").
  void write(std::string_view bytes) const;
  /// Flushes the temporary to the disk (fsync: where the file system only
  /// finds out then that it has no room, that is an error here) and moves
  /// it onto the target (atomic within a directory). Throws
  /// std::runtime_error naming the target on failure, removing the
  /// temporary; the target keeps what it held.
  void commit();

 private:
  // Removes the temporary and throws "target: what" and errno's reason.
  [[noreturn]] void discard_and_throw(const std::string& what);

  std::string m_target, m_temporary;
  int m_slot = -1;  // in the signal handler's list of temporaries
  bool m_committed = false;
};

/// A helper process the program started (an encoder it feeds), listed
/// while this object lives so that the signal handlers of
/// install_signal_cleanup kill it (SIGKILL) rather than leave it running
/// after the program: a hung helper would otherwise outlive it. The
/// owner still stops and waits for it in the ordinary way.
class ChildProcess {
 public:
  explicit ChildProcess(pid_t pid);
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

 private:
  int m_slot = -1;
};

/// Installs handlers for SIGINT, SIGTERM and SIGHUP that remove every live
/// OutputFile's temporary, kill every live ChildProcess and then end the
/// program as the signal would have (default action, re-raised).
void install_signal_cleanup();

/// Whether two paths name one file, however spelled (./b.exr, b.exr,
/// $PWD/b.exr, through a link): the same device and inode where both
/// exist, else the same absolute path once the parts that exist are
/// resolved.
bool same_file(const std::string& a, const std::string& b);

/// Writes `text` to `path` through an OutputFile. Throws std::runtime_error
/// naming the file on failure.
void write_text_file(const std::string& path, const std::string& text);

}  // namespace sol::programs
