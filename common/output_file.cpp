#include "output_file.hpp"

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace sol::programs {
namespace {

// The temporaries alive now, for the signal handler: fixed storage (no
// allocation in the handler), each slot free (0), being filled (1) or
// holding a path (2). Lock-free atomics are safe in a handler.
constexpr int kSlots = 16;
constexpr std::size_t kPathBytes = 4096;
char g_paths[kSlots][kPathBytes];
std::atomic<int> g_state[kSlots];

int claim_slot(const std::string& path) {
  if (path.size() >= kPathBytes) return -1;  // too long to list: the destructor still removes it
  for (int i = 0; i < kSlots; ++i) {
    int expected = 0;
    if (g_state[i].compare_exchange_strong(expected, 1)) {
      std::memcpy(g_paths[i], path.c_str(), path.size() + 1);
      g_state[i].store(2);
      return i;
    }
  }
  return -1;
}

void release_slot(int slot) {
  if (slot >= 0) g_state[slot].store(0);
}

// The helper processes alive now (an encoder the program feeds), for the
// signal handler: each slot 0 or a process id.
std::atomic<pid_t> g_children[kSlots];

extern "C" void remove_temporaries_and_reraise(int signal) {
  for (int i = 0; i < kSlots; ++i) {
    if (g_state[i].load() == 2) ::unlink(g_paths[i]);
  }
  // A helper that would outlive us (a hung encoder): stopped, not waited for.
  for (int i = 0; i < kSlots; ++i) {
    if (const pid_t child = g_children[i].load(); child > 0) ::kill(child, SIGKILL);
  }
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

}  // namespace

OutputFile::OutputFile(std::string target) : m_target(std::move(target)) {
  namespace fs = std::filesystem;
  const fs::path target_path(m_target);
  std::error_code ec;
  if (m_target.empty()) throw std::runtime_error("an output file name is empty");
  if (fs::is_directory(target_path, ec)) throw std::runtime_error(m_target + ": cannot write: it is a directory");
  const fs::path directory = target_path.has_parent_path() ? target_path.parent_path() : fs::path(".");
  std::string hidden = target_path.filename().string();
  hidden.insert(hidden.begin(), '.');
  hidden.append(".XXXXXX");
  const std::string pattern = (directory / hidden).string();
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  const int fd = ::mkstemp(name.data());
  if (fd < 0) throw std::runtime_error(m_target + ": cannot write: " + std::strerror(errno));
  // mkstemp makes the file private (0600); the output gets the usual mode.
  const mode_t mask = ::umask(0);
  ::umask(mask);
  ::fchmod(fd, static_cast<mode_t>(0666) & ~mask);
  ::close(fd);
  m_temporary = name.data();
  m_slot = claim_slot(m_temporary);
}

OutputFile::~OutputFile() {
  if (!m_committed) ::unlink(m_temporary.c_str());
  release_slot(m_slot);
}

void OutputFile::write(std::string_view bytes) const {
  const int fd = ::open(m_temporary.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
  if (fd < 0) throw std::runtime_error(m_target + ": cannot write: " + std::strerror(errno));
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const std::string reason = n < 0 ? std::strerror(errno) : "the disk took no more data";
      ::close(fd);
      throw std::runtime_error(m_target + ": cannot write: " + reason);
    }
    done += static_cast<std::size_t>(n);
  }
  if (::close(fd) != 0) throw std::runtime_error(m_target + ": cannot write: " + std::strerror(errno));
}

void OutputFile::discard_and_throw(const std::string& what) {
  const std::string reason = std::strerror(errno);
  ::unlink(m_temporary.c_str());
  m_committed = true;  // nothing left to remove
  release_slot(m_slot);
  m_slot = -1;
  throw std::runtime_error(m_target + ": " + what + reason);
}

void OutputFile::commit() {
  if (m_committed) return;
  const int fd = ::open(m_temporary.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) discard_and_throw("cannot write: ");
  if (::fsync(fd) != 0) {
    const int error = errno;
    ::close(fd);
    errno = error;
    discard_and_throw("cannot write: ");
  }
  ::close(fd);
  if (std::rename(m_temporary.c_str(), m_target.c_str()) != 0) discard_and_throw("cannot move the finished file into place: ");
  m_committed = true;
  release_slot(m_slot);
  m_slot = -1;
}

ChildProcess::ChildProcess(pid_t pid) {
  for (int i = 0; i < kSlots; ++i) {
    pid_t expected = 0;
    if (g_children[i].compare_exchange_strong(expected, pid)) {
      m_slot = i;
      return;
    }
  }
}

ChildProcess::~ChildProcess() {
  if (m_slot >= 0) g_children[m_slot].store(0);
}

void install_signal_cleanup() {
  for (int signal : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction previous {};
    sigaction(signal, nullptr, &previous);
    if (previous.sa_handler == SIG_IGN) continue;  // ignored by whoever started us (e.g. nohup): stays so
    struct sigaction action {};
    action.sa_handler = remove_temporaries_and_reraise;
    sigemptyset(&action.sa_mask);
    action.sa_flags = 0;
    sigaction(signal, &action, nullptr);
  }
}

bool same_file(const std::string& a, const std::string& b) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec) && !ec;
  const fs::path x = fs::weakly_canonical(fs::absolute(a, ec), ec);
  if (ec) return a == b;
  const fs::path y = fs::weakly_canonical(fs::absolute(b, ec), ec);
  if (ec) return a == b;
  return x == y;
}

void write_text_file(const std::string& path, const std::string& text) {
  OutputFile file(path);
  file.write(text);
  file.commit();
}

}  // namespace sol::programs
