#include "sol/file_io.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace sol {

std::optional<std::string> read_regular_file(const std::filesystem::path& path, std::uintmax_t max_bytes,
                                             FileRefusal* why) {
  using Kind = FileRefusal::Kind;
  auto refuse = [&](Kind kind, const std::string& text) -> std::optional<std::string> {
    if (why) *why = {kind, text};
    return std::nullopt;
  };
  const auto too_large = [&] { return refuse(Kind::TooLarge, "larger than " + std::to_string(max_bytes) + " bytes"); };
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return errno == ENOENT ? refuse(Kind::Missing, "no such file") : refuse(Kind::Error, std::strerror(errno));
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) return refuse(Kind::Error, std::strerror(errno));
  if (S_ISDIR(st.st_mode)) return refuse(Kind::Directory, "a directory");
  if (!S_ISREG(st.st_mode)) return refuse(Kind::NotRegular, "not a regular file (a FIFO, a device or a socket)");
  if (static_cast<std::uintmax_t>(st.st_size) > max_bytes) return too_large();
  std::string data(static_cast<std::size_t>(st.st_size), '\0');
  std::size_t done = 0;
  while (true) {
    if (done == data.size()) {
      // At the size fstat gave: read one more byte to see that it ends here.
      char extra = 0;
      const ssize_t n = ::read(fd, &extra, 1);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) return refuse(Kind::Error, std::strerror(errno));
      if (n == 0) break;
      if (data.size() >= max_bytes) return too_large();
      data.push_back(extra);  // it grew: go on, within the bound
      ++done;
      data.resize(std::min<std::uintmax_t>(max_bytes, data.size() + 65536));
      continue;
    }
    const ssize_t n = ::read(fd, data.data() + done, data.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return refuse(Kind::Error, std::strerror(errno));
    if (n == 0) {  // it shrank
      data.resize(done);
      break;
    }
    done += static_cast<std::size_t>(n);
  }
  return data;
}

}  // namespace sol
