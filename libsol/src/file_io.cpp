#include "sol/file_io.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace sol {

std::optional<std::string> read_regular_file(const std::filesystem::path& path, std::uintmax_t max_bytes,
                                             std::string* why) {
  auto refuse = [&](const std::string& reason) -> std::optional<std::string> {
    if (why) *why = reason;
    return std::nullopt;
  };
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return refuse(errno == ENOENT ? "no such file" : std::strerror(errno));
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) return refuse(std::strerror(errno));
  if (S_ISDIR(st.st_mode)) return refuse("a directory");
  if (!S_ISREG(st.st_mode)) return refuse("not a regular file (a FIFO, a device or a socket)");
  if (static_cast<std::uintmax_t>(st.st_size) > max_bytes) {
    return refuse("larger than " + std::to_string(max_bytes) + " bytes");
  }
  std::string data(static_cast<std::size_t>(st.st_size), '\0');
  std::size_t done = 0;
  while (true) {
    if (done == data.size()) {
      // At the size fstat gave: read one more byte to see that it ends here.
      char extra = 0;
      const ssize_t n = ::read(fd, &extra, 1);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) return refuse(std::strerror(errno));
      if (n == 0) break;
      if (data.size() >= max_bytes) return refuse("larger than " + std::to_string(max_bytes) + " bytes");
      data.push_back(extra);  // it grew: go on, within the bound
      ++done;
      data.resize(std::min<std::uintmax_t>(max_bytes, data.size() + 65536));
      continue;
    }
    const ssize_t n = ::read(fd, data.data() + done, data.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return refuse(std::strerror(errno));
    if (n == 0) {  // it shrank
      data.resize(done);
      break;
    }
    done += static_cast<std::size_t>(n);
  }
  return data;
}

}  // namespace sol
