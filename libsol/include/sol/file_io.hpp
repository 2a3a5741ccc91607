// Reading files that a user, another process or a full disk may have made
// anything: a FIFO that would block, a link to a device that never ends
// (/dev/zero), a directory, a sparse file of a terabyte. Scene and path
// files, the programs' caches and a film's manifest are read through it.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace sol {

/// Why read_regular_file read nothing: the kind, for a caller's own
/// message, and the same in words.
struct FileRefusal {
  enum class Kind {
    Missing,     ///< "no such file"
    Directory,   ///< "a directory"
    NotRegular,  ///< "not a regular file (a FIFO, a device or a socket)"
    TooLarge,    ///< "larger than N bytes" (N the caller's bound)
    Error,       ///< the system's error (permissions, I/O)
  };
  Kind kind = Kind::Error;
  std::string text;
};

/// The bytes of `path` when it is a regular file of at most `max_bytes`;
/// otherwise none, with `why` (when given) saying what it is instead.
/// Never blocks on what is not a regular file: it is opened without
/// waiting (O_NONBLOCK) and checked on the open descriptor (fstat), so
/// that a file swapped for a FIFO in between is caught too, and never
/// reads more than max_bytes + 1 bytes (a file that grows while it is read
/// is refused).
std::optional<std::string> read_regular_file(const std::filesystem::path& path, std::uintmax_t max_bytes,
                                             FileRefusal* why = nullptr);

}  // namespace sol
