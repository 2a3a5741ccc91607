// What the programs share (Sol::programs, common/): output files that are
// complete or absent, also when a signal ends the program.
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <OpenImageIO/imageio.h>

#include "image_file.hpp"
#include "output_file.hpp"

namespace fs = std::filesystem;

namespace {

// A fresh directory per test under the system's temporary directory.
fs::path fresh_directory(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("sol-programs-test-" + std::to_string(::getpid()) + "-" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string read(const fs::path& p) {
  std::ifstream in(p);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

int entries(const fs::path& d) {
  int n = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(d)) ++n;
  return n;
}

}  // namespace

TEST(OutputFile, CommitReplacesTheTargetAndNothingElseIsLeft) {
  const fs::path d = fresh_directory("commit");
  const fs::path target = d / "out.txt";
  std::ofstream(target) << "before";
  {
    sol::programs::OutputFile file(target.string());
    EXPECT_NE(file.path(), target.string());
    EXPECT_EQ(fs::path(file.path()).parent_path(), d);  // beside the target: rename stays atomic
    std::ofstream(file.path()) << "after";
    EXPECT_EQ(read(target), "before");  // untouched until the commit
    file.commit();
  }
  EXPECT_EQ(read(target), "after");
  EXPECT_EQ(entries(d), 1);
  fs::remove_all(d);
}

TEST(OutputFile, UncommittedLeavesTheTargetAsItWas) {
  const fs::path d = fresh_directory("abandon");
  const fs::path target = d / "out.txt";
  std::ofstream(target) << "before";
  {
    sol::programs::OutputFile file(target.string());
    std::ofstream(file.path()) << "half";
  }
  EXPECT_EQ(read(target), "before");
  EXPECT_EQ(entries(d), 1);
  fs::remove_all(d);
}

TEST(OutputFile, TemporariesAreFreshFilesNeverLinks) {
  const fs::path d = fresh_directory("fresh");
  const fs::path target = d / "out.txt";
  {
    sol::programs::OutputFile a(target.string()), b(target.string());
    EXPECT_NE(a.path(), b.path());  // unpredictable, created exclusively
    struct stat s {};
    ASSERT_EQ(::lstat(a.path().c_str(), &s), 0);
    EXPECT_TRUE(S_ISREG(s.st_mode));
    // The usual mode of a new file (0666 less the umask), not mkstemp's 0600.
    const mode_t mask = ::umask(0);
    ::umask(mask);
    EXPECT_EQ(s.st_mode & 0777, 0666 & ~mask);
  }
  EXPECT_EQ(entries(d), 0);
  fs::remove_all(d);
}

TEST(OutputFile, RefusesDirectoriesAndMissingDirectories) {
  const fs::path d = fresh_directory("refuse");
  try {
    sol::programs::OutputFile file(d.string());
    ADD_FAILURE() << "a directory was accepted as an output file";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("it is a directory"), std::string::npos) << e.what();
  }
  EXPECT_THROW(sol::programs::OutputFile((d / "no" / "such.txt").string()), std::runtime_error);
  EXPECT_EQ(entries(d), 0);
  fs::remove_all(d);
}

TEST(OutputFile, WriteTextFileIsCompleteOrAbsent) {
  const fs::path d = fresh_directory("text");
  sol::programs::write_text_file((d / "a.csv").string(), "x,y\n1,2\n");
  EXPECT_EQ(read(d / "a.csv"), "x,y\n1,2\n");
  EXPECT_THROW(sol::programs::write_text_file(d.string(), "x"), std::runtime_error);
  EXPECT_EQ(entries(d), 1);
  fs::remove_all(d);
}

// A child process writes half a file and is ended by each signal: the
// handlers remove its temporary, the target stays as it was, and the child
// dies of that signal (the default action, re-raised).
TEST(OutputFile, SignalsRemoveTheTemporaries) {
  for (int signal : {SIGINT, SIGTERM, SIGHUP}) {
    const fs::path d = fresh_directory("signal" + std::to_string(signal));
    const fs::path target = d / "out.png";
    std::ofstream(target) << "before";
    int pipe_fds[2];
    ASSERT_EQ(::pipe(pipe_fds), 0);
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      ::close(pipe_fds[0]);
      std::signal(signal, SIG_DFL);  // as a program starts
      sol::programs::install_signal_cleanup();
      sol::programs::OutputFile file(target.string());
      std::ofstream(file.path()) << "half an image";
      const std::string path = file.path() + "\n";
      if (::write(pipe_fds[1], path.data(), path.size()) < 0) ::_exit(3);
      std::raise(signal);
      ::_exit(4);  // not reached: the signal ends the child
    }
    ::close(pipe_fds[1]);
    char buffer[4096] = {};
    const ssize_t got = ::read(pipe_fds[0], buffer, sizeof buffer - 1);
    ::close(pipe_fds[0]);
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_GT(got, 1);
    const std::string temporary(buffer, static_cast<std::size_t>(got) - 1);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == signal) << "signal " << signal << ", status " << status;
    EXPECT_FALSE(fs::exists(temporary)) << temporary;
    EXPECT_EQ(read(target), "before");
    EXPECT_EQ(entries(d), 1);
    fs::remove_all(d);
  }
}

// No NaN or infinity reaches a file: written as 0 and counted.
TEST(ImageFile, NonFiniteValuesAreWrittenAsZeroAndCounted) {
  const fs::path d = fresh_directory("finite");
  const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<float> pixels = {0.5f, nan, 0.25f, 1.0f, -inf, 0.125f, inf, 1.0f};  // 2x1 RGBA
  const std::string path = (d / "a.exr").string();
  EXPECT_EQ(sol::programs::write_image(path, 2, 1, {"R", "G", "B", "A"}, pixels, false), 3u);
  auto in = OIIO::ImageInput::open(path);
  ASSERT_TRUE(in);
  std::vector<float> back(8);
  ASSERT_TRUE(in->read_image(0, 0, 0, 4, OIIO::TypeDesc::FLOAT, back.data()));
  const std::vector<float> expected = {0.5f, 0.0f, 0.25f, 1.0f, 0.0f, 0.125f, 0.0f, 1.0f};
  EXPECT_EQ(back, expected);
  fs::remove_all(d);
}
