#include "output_file.hpp"

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <vector>

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

extern "C" void remove_temporaries_and_reraise(int signal) {
  for (int i = 0; i < kSlots; ++i) {
    if (g_state[i].load() == 2) ::unlink(g_paths[i]);
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

void OutputFile::commit() {
  if (m_committed) return;
  if (std::rename(m_temporary.c_str(), m_target.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    ::unlink(m_temporary.c_str());
    m_committed = true;  // nothing left to remove
    release_slot(m_slot);
    m_slot = -1;
    throw std::runtime_error(m_target + ": cannot move the finished file into place: " + reason);
  }
  m_committed = true;
  release_slot(m_slot);
  m_slot = -1;
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

void write_text_file(const std::string& path, const std::string& text) {
  OutputFile file(path);
  std::FILE* f = std::fopen(file.path().c_str(), "w");
  if (!f) throw std::runtime_error(path + ": cannot write: " + std::strerror(errno));
  const bool written = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  if (std::fclose(f) != 0 || !written) throw std::runtime_error(path + ": cannot write: " + std::strerror(errno));
  file.commit();
}

}  // namespace sol::programs
