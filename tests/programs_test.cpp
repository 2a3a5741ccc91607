// What the programs share (Sol::programs, common/): output files that are
// complete or absent, also when a signal ends the program.
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <fstream>
#include <limits>
#include <optional>
#include <random>
#include <span>
#include <thread>
#include <chrono>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <OpenImageIO/imageio.h>

#include "adaptive_scale.hpp"
#include "frame_stats.hpp"
#include "image_file.hpp"
#include "output_file.hpp"
#include "progress.hpp"
#include "sampling.hpp"
#include "support/batch_guides.hpp"

#include <sol/render.hpp>
#include <sol/renderer.hpp>
#include <sol/error.hpp>
#include <sol/scene.hpp>

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

// A full disk, as a writer sees it: every write past `bytes` fails (the
// file size limit, RLIMIT_FSIZE, with SIGXFSZ ignored: write() returns
// EFBIG as it returns ENOSPC on a full disk). The soft limit is lowered for
// `write` alone and put back (a child process would inherit the locks of
// OpenImageIO's threads). Answers 0 when `write` threw std::runtime_error,
// 1 when it returned, 2 on another exception.
int write_on_a_full_disk(const std::function<void()>& write, rlim_t bytes) {
  rlimit before{};
  if (::getrlimit(RLIMIT_FSIZE, &before) != 0) return -1;
  const auto previous_handler = std::signal(SIGXFSZ, SIG_IGN);
  rlimit limited = before;
  limited.rlim_cur = bytes;
  if (::setrlimit(RLIMIT_FSIZE, &limited) != 0) return -1;
  int status = 1;
  try {
    write();
  } catch (const std::runtime_error&) {
    status = 0;
  } catch (...) {
    status = 2;
  }
  ::setrlimit(RLIMIT_FSIZE, &before);
  std::signal(SIGXFSZ, previous_handler);
  return status;
}

// On a full disk every writer fails with an error, the target keeps what it
// held and no temporary is left: text files, and images in the usual
// formats (PNG and JPEG, whose writers left empty files there
// and said nothing), EXR and TIFF. The images are 64 x 48 of noise:
// larger than the 4 KB allowed in every format.
TEST(OutputFile, AFullDiskKeepsTheTargetAndLeavesNoTemporary) {
  std::vector<float> noise(64 * 48 * 4);
  std::uint32_t state = 12345;
  for (float& v : noise) {
    state = state * 1664525u + 1013904223u;
    v = static_cast<float>(state >> 8) / 16777216.0f;
  }
  for (const std::string name : {"out.txt", "out.png", "out.jpg", "out.exr", "out.tif"}) {
    const fs::path d = fresh_directory("full-" + name);
    const fs::path target = d / name;
    std::ofstream(target) << "before";
    const int status = write_on_a_full_disk(
        [&] {
          if (name == "out.txt") {
            sol::programs::write_text_file(target.string(), std::string(64 * 1024, 'x'));
          } else {
            sol::programs::write_image(target.string(), 64, 48, {"R", "G", "B", "A"}, noise, true);
          }
        },
        4096);
    EXPECT_EQ(status, 0) << name << ": the write did not fail (1) or failed otherwise";
    EXPECT_EQ(read(target), "before") << name;
    EXPECT_EQ(entries(d), 1) << name << ": a temporary was left";
    // With room, the same write succeeds (the limit was what failed it).
    if (name == "out.txt") {
      sol::programs::write_text_file(target.string(), "after");
      EXPECT_EQ(read(target), "after");
    } else {
      sol::programs::write_image(target.string(), 64, 48, {"R", "G", "B", "A"}, noise, true);
      EXPECT_GT(fs::file_size(target), 4096u) << name;
    }
    fs::remove_all(d);
  }
}

// Two spellings of one file are one file; two files are two.
TEST(OutputFile, SameFileWhateverTheSpelling) {
  const fs::path d = fresh_directory("same");
  const fs::path b = d / "b.exr";
  fs::create_directories(d / "sub");
  fs::create_directory_symlink(d, d / "link");
  for (const bool exists : {false, true}) {
    if (exists) std::ofstream(b) << "x";
    EXPECT_TRUE(sol::programs::same_file(b.string(), (d / "." / "b.exr").string())) << exists;
    EXPECT_TRUE(sol::programs::same_file(b.string(), (d / "sub" / ".." / "b.exr").string())) << exists;
    EXPECT_TRUE(sol::programs::same_file(b.string(), (d / "link" / "b.exr").string())) << exists;
    EXPECT_FALSE(sol::programs::same_file(b.string(), (d / "c.exr").string())) << exists;
  }
  const fs::path here = fs::current_path();
  fs::current_path(d);
  EXPECT_TRUE(sol::programs::same_file("b.exr", "./b.exr"));
  EXPECT_TRUE(sol::programs::same_file("b.exr", b.string()));
  EXPECT_TRUE(sol::programs::same_file("new.exr", "./new.exr"));  // neither exists
  EXPECT_TRUE(sol::programs::same_file("new.exr", (d / "new.exr").string()));
  EXPECT_FALSE(sol::programs::same_file("new.exr", "sub/new.exr"));
  fs::current_path(here);
  fs::remove_all(d);
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

// RGBA into formats without alpha (Radiance .hdr, .ppm) is written as RGB
// (both refused the image after the render): the colour as written, within
// each format's own precision (RGBE: an 8-bit mantissa shared by the
// three, 2^-8 of the largest; 8-bit sRGB: half a step of 1/255 after the
// encoding, compared here in the encoded values).
TEST(ImageFile, RgbaIntoFormatsWithoutAlphaKeepsTheColour) {
  const fs::path d = fresh_directory("noalpha");
  const std::vector<float> pixels = {0.5f, 0.25f, 0.125f, 1.0f, 2.0f, 0.75f, 0.0625f, 1.0f};  // 2x1 RGBA, linear
  for (const char* name : {"a.hdr", "a.ppm"}) {
    const std::string path = (d / name).string();
    ASSERT_NO_THROW(sol::programs::write_image(path, 2, 1, {"R", "G", "B", "A"}, pixels, true)) << name;
    auto in = OIIO::ImageInput::open(path);
    ASSERT_TRUE(in) << name;
    ASSERT_EQ(in->spec().nchannels, 3) << name;
    std::vector<float> back(6);
    ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, back.data())) << name;
    const bool hdr = std::string(name) == "a.hdr";
    for (int p = 0; p < 2; ++p) {
      for (int c = 0; c < 3; ++c) {
        const float written = pixels[static_cast<std::size_t>(4 * p + c)];
        const float got = back[static_cast<std::size_t>(3 * p + c)];
        if (hdr) {
          const float largest = std::max({pixels[4 * p], pixels[4 * p + 1], pixels[4 * p + 2]});
          EXPECT_NEAR(got, written, largest / 256.0f) << name << " " << p << " " << c;
        } else {
          // sRGB bytes, read back as value / 255: the encoding of the clamped colour.
          const float v = std::min(written, 1.0f);
          const float encoded = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
          EXPECT_NEAR(got, encoded, 0.5f / 255.0f + 1e-6f) << name << " " << p << " " << c;
        }
      }
    }
  }
  fs::remove_all(d);
}

// The display (exposure and tone curve) of 8-bit files, against the
// curves computed here from their definitions: clamp is the value cut at 1
// (the sRGB encoding of min(v 2^e, 1)); aces is Narkowicz's rational fit,
// (x (2.51 x + 0.03)) / (x (2.43 x + 0.59) + 0.14) at x = v 2^e; half a
// step of 1/255 after the encoding. The EXR of the same call is the linear
// input whatever the display; the clipped pixels are those with a channel
// where the curve passes 1 (clamp: v 2^e > 1; aces: x > 7.2417, the
// positive root of 0.08 x^2 - 0.56 x - 0.14).
TEST(ImageFile, EightBitFilesTakeTheDisplayAndFloatFilesStayLinear) {
  const fs::path d = fresh_directory("display");
  const std::vector<float> pixels = {0.05f, 0.18f, 0.5f, 1.0f, 0.9f, 2.0f, 4.0f, 1.0f, 9.0f, 0.3f, 0.01f, 1.0f};  // 3x1
  const double aces_white = (0.56 + std::sqrt(0.56 * 0.56 + 4 * 0.08 * 0.14)) / 0.16;
  struct Case {
    sol::Display display;
    int clipped;
  };
  const Case cases[] = {{{0.0, sol::Tone::Clamp}, 2}, {{-1.0, sol::Tone::Clamp}, 2}, {{-2.0, sol::Tone::Clamp}, 1},
                        {{0.0, sol::Tone::Aces}, 1}, {{1.5, sol::Tone::Aces}, 2}, {{-1.0, sol::Tone::Aces}, 0}};
  for (const Case& c : cases) {
    const std::string label = std::to_string(c.display.exposure) + " " + sol::tone_name(c.display.tone);
    for (const char* name : {"a.png", "a.exr"}) {
      const std::string path = (d / name).string();
      sol::programs::OutputFile file(path);
      sol::programs::ImageWriter writer(file, 3, 1, {"R", "G", "B", "A"}, true, false, c.display);
      writer.write_rows(0, 1, pixels);
      writer.finish();
      file.commit();
      auto in = OIIO::ImageInput::open(path);
      ASSERT_TRUE(in);
      std::vector<float> back(12);
      ASSERT_TRUE(in->read_image(0, 0, 0, 4, OIIO::TypeDesc::FLOAT, back.data()));
      if (std::string(name) == "a.exr") {
        EXPECT_EQ(back, pixels) << label;
        EXPECT_EQ(writer.clipped(), 0u) << label;
        continue;
      }
      EXPECT_EQ(writer.clipped(), static_cast<std::size_t>(c.clipped)) << label;
      for (std::size_t k = 0; k < 12; ++k) {
        if (k % 4 == 3) continue;
        const double x = pixels[k] * std::exp2(c.display.exposure);
        const double shown = c.display.tone == sol::Tone::Clamp
                                 ? std::min(x, 1.0)
                                 : std::min((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 1.0);
        if (c.display.tone == sol::Tone::Aces) {
          EXPECT_EQ(shown >= 1.0, x >= aces_white) << label;
        }
        const double encoded = shown <= 0.0031308 ? 12.92 * shown : 1.055 * std::pow(shown, 1.0 / 2.4) - 0.055;
        EXPECT_NEAR(back[k], encoded, 0.5 / 255.0 + 1e-6) << label << " " << k;
      }
    }
  }
  fs::remove_all(d);
}

// ImageWriter takes an image band by band, on the caller's thread or its
// worker's, and writes the file write_image writes of the whole (the same
// pixels read back, in PNG's 8-bit sRGB and EXR's floats); rows out of turn
// and a file finished short are errors; a writer given up unfinished (a
// failed render) leaves its temporary behind for the OutputFile to remove,
// and no target.
TEST(ImageFile, RowsWrittenBandByBandAreTheWholeImage) {
  const fs::path d = fresh_directory("bands");
  const int w = 37, h = 150;  // bands of 64 rows inside the writer: 64 + 64 + 22
  std::vector<float> pixels(static_cast<std::size_t>(w) * h * 4);
  for (std::size_t k = 0; k < pixels.size(); ++k) pixels[k] = static_cast<float>((k * 7919) % 1000) / 900.0f;
  auto read = [](const std::string& path) {
    auto in = OIIO::ImageInput::open(path);
    std::vector<float> back(static_cast<std::size_t>(in->spec().width) * in->spec().height * in->spec().nchannels);
    EXPECT_TRUE(in->read_image(0, 0, 0, in->spec().nchannels, OIIO::TypeDesc::FLOAT, back.data()));
    return back;
  };
  for (const char* ext : {".png", ".exr"}) {
    const std::string whole = (d / (std::string("whole") + ext)).string();
    sol::programs::write_image(whole, w, h, {"R", "G", "B", "A"}, pixels, true);
    for (bool worker : {false, true}) {
      const std::string banded = (d / (std::string(worker ? "worker" : "caller") + ext)).string();
      sol::programs::OutputFile file(banded);
      sol::programs::ImageWriter writer(file, w, h, {"R", "G", "B", "A"}, true, worker);
      for (int y = 0; y < h; y += 40) {  // uneven bands: 40, 40, 40, 30
        const int rows = std::min(40, h - y);
        writer.write_rows(y, rows, std::span(pixels).subspan(static_cast<std::size_t>(y) * w * 4,
                                                              static_cast<std::size_t>(rows) * w * 4));
      }
      EXPECT_EQ(writer.finish(), 0u);
      file.commit();
      EXPECT_EQ(read(banded), read(whole)) << banded;
    }
  }
  {
    sol::programs::OutputFile file((d / "turns.png").string());
    sol::programs::ImageWriter writer(file, w, h, {"R", "G", "B", "A"}, true);
    const auto rows = std::span(pixels).subspan(0, static_cast<std::size_t>(w) * 4 * 10);
    EXPECT_THROW(writer.write_rows(10, 10, rows), std::runtime_error);  // row 0 first
    writer.write_rows(0, 10, rows);
    EXPECT_THROW(writer.finish(), std::runtime_error);  // 10 of 150 rows
  }
  for (bool worker : {false, true}) {
    {
      sol::programs::OutputFile file((d / "given-up.png").string());
      sol::programs::ImageWriter writer(file, w, h, {"R", "G", "B", "A"}, true, worker);
      writer.write_rows(0, 40, std::span(pixels).subspan(0, static_cast<std::size_t>(w) * 4 * 40));
    }  // destroyed unfinished, as when a render throws
    EXPECT_FALSE(fs::exists(d / "given-up.png"));
  }
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(d)) ++files;
  EXPECT_EQ(files, 6u);  // whole, caller and worker of each format; no temporary left
  fs::remove_all(d);
}

// The time-left estimate against the truth of a render whose start is slow
// (a kernel compiled on a cold cache: 11.5 s before the first band of 4 %,
// then 1 s for the rest, as on lavapipe) and one that runs evenly: after
// 10 % done, within a factor 2 of the time truly left.
// The noise estimate against noise of a known size: half-images a and b,
// each the mean of n samples of value mu plus Gaussian noise of deviation
// sigma, so the mean of both has the relative error sigma / (mu sqrt(2 n)).
// The per-pixel estimate (a 3 x 3 neighbourhood: a chi distribution of 9
// degrees of freedom scaled by that error) has its median at 0.963 of it;
// the image's, the 99th percentile, at 1.55 of it (sqrt(21.67 / 9)) inside
// and up to 1.82 at the corners (4 degrees: sqrt(13.28 / 4)), so between.
TEST(Sampling, TheNoiseEstimateMeasuresTheErrorOfTheMean) {
  const int w = 64, h = 48, n = 8;
  const double mu = 0.4, sigma = 0.3;
  std::mt19937_64 random(7);
  std::normal_distribution<double> noise(0.0, sigma / std::sqrt(n));
  std::vector<double> a(4 * w * h), b(4 * w * h);
  for (std::size_t k = 0; k < a.size(); ++k) {
    a[k] = k % 4 == 3 ? 1.0 : mu + noise(random);
    b[k] = k % 4 == 3 ? 1.0 : mu + noise(random);
  }
  // The luminance of a grey pixel is its value; its error is sigma / sqrt(2 n) too (the
  // channels' noise is independent: the luminance weights' squares sum to 0.5645).
  const double weights = std::sqrt(0.2126 * 0.2126 + 0.7152 * 0.7152 + 0.0722 * 0.0722);
  const double truth = weights * sigma / std::sqrt(2.0 * n) / mu;
  std::vector<double> e = sol::programs::pixel_noise(a, b, w, h);
  std::nth_element(e.begin(), e.begin() + static_cast<std::ptrdiff_t>(e.size() / 2), e.end());
  const double median = e[e.size() / 2], image = sol::programs::noise_estimate(a, b, w, h);
  std::printf("relative error %.4f; pixel estimates' median %.4f, the image's %.4f\n", truth, median, image);
  EXPECT_NEAR(median / truth, 0.963, 0.08);
  EXPECT_GT(image / truth, 1.45);
  EXPECT_LT(image / truth, 1.9);
}

// Batches until a noise target: synthetic renders whose samples carry known
// noise stop once the estimate is at the target, with the samples that
// needs (the error falls as 1 / sqrt(samples)), as whole pairs; the mean of
// the batches is the mean of the samples; the limits hold.
TEST(Sampling, BatchesStopAtTheTargetOrTheLimit) {
  const int w = 32, h = 24;
  std::mt19937_64 random(11);
  std::vector<std::pair<int, int>> ranges;
  const auto batch = [&](int first, int count, bool aovs) {
    ranges.emplace_back(first, count);
    sol::RenderResult r;
    r.width = w;
    r.height = h;
    std::normal_distribution<double> noise(0.0, 0.5 / std::sqrt(count));  // per sample: 0.5 about 0.5
    r.rgba.resize(4 * w * h);
    for (std::size_t k = 0; k < r.rgba.size(); ++k) r.rgba[k] = k % 4 == 3 ? 1.0f : static_cast<float>(0.5 + noise(random));
    if (aovs) r.object.assign(static_cast<std::size_t>(w * h), 1.0f);
    return r;
  };
  sol::programs::SamplingGoal goal;
  goal.noise = 0.05;
  sol::programs::SamplingReport report;
  const sol::RenderResult r = sol::programs::render_batches(batch, true, goal, report);
  // 1.55 x the error 0.75 x 0.5 / sqrt(N) / 0.5 at most 0.05: N >= 540; pairs 1, 2, 4, ... make 2 (2^p - 1).
  std::printf("samples %d, estimate %.4f\n", report.samples, report.noise);
  EXPECT_TRUE(report.noise_reached);
  EXPECT_LE(report.noise, 0.05);
  EXPECT_GE(report.samples, 254);
  EXPECT_LE(report.samples, 2046);
  int next = 0;
  for (std::size_t i = 0; i < ranges.size(); ++i) {
    EXPECT_EQ(ranges[i].first, next);  // consecutive, in equal pairs
    if (i % 2 == 1) {
      EXPECT_EQ(ranges[i].second, ranges[i - 1].second);
    }
    next += ranges[i].second;
  }
  EXPECT_EQ(next, report.samples);
  EXPECT_EQ(r.object.size(), static_cast<std::size_t>(w * h));  // the first batch's AOVs
  double mean = 0.0;
  for (std::size_t k = 0; k < r.rgba.size(); k += 4) mean += r.rgba[k];
  EXPECT_NEAR(mean / (w * h), 0.5, 0.01);
  // At most max_samples; at least min_samples.
  ranges.clear();
  goal.noise = 1e-4;
  goal.max_samples = 40;
  sol::programs::render_batches(batch, false, goal, report);
  EXPECT_LE(report.samples, 40);
  EXPECT_FALSE(report.noise_reached);
  goal = {};
  goal.min_samples = 9;
  sol::programs::render_batches(batch, false, goal, report);
  EXPECT_EQ(report.samples, 10);
  // A time limit: batches of 5 ms a sample stop before 0.3 s (the next pair
  // predicted from those before; 20 % for a loaded machine's sleeps).
  ranges.clear();
  const auto slow = [&](int first, int count, bool aovs) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5 * count));
    return batch(first, count, aovs);
  };
  goal = {};
  goal.seconds = 0.3;
  sol::programs::render_batches(slow, false, goal, report);
  EXPECT_LT(report.seconds, 0.36);
  EXPECT_GE(report.samples, 30);  // 5 ms a sample: 60 fit; pairs 1, 2, 4, 8 make 30 in 0.15 s
}

TEST(Sampling, TheCpuRenderersBatchesJoinTheirGuides) {
  // (Each batch's means are floats: their weighted mean is the one
  // render's to a few float roundings of values below 2.)
  sol::CpuRenderer cpu;
  sol::test::expect_batches_join_the_guides(cpu, 1e-6);
}

// A path-traced render stopped at a noise target, against a reference of
// 2048 paths a pixel (its own error about a tenth of the target's): the
// actual relative error of the lit pixels (luminance above 1e-3), in RMS,
// is within the target, which bounds the 99th percentile of the estimate.
TEST(Sampling, ARenderStoppedAtTheTargetIsWithinItOfTheReference) {
  const sol::Scene scene = sol::preset_scene("plane");
  sol::CpuRenderer renderer(scene);
  const sol::RenderOptions base{.width = 16, .height = 12, .transport = sol::Transport::Path, .seed = 5, .aovs = false};
  const auto batch = [&](int first, int count, bool) {
    sol::RenderOptions o = base;
    o.first_sample = first;
    o.samples = count;
    return renderer.render(scene.camera, o);
  };
  sol::programs::SamplingGoal goal;
  goal.noise = 0.2;
  sol::programs::SamplingReport report;
  const sol::RenderResult r = sol::programs::render_batches(batch, false, goal, report);
  sol::RenderOptions many = base;
  many.samples = 2048;
  many.seed = 99;
  const sol::RenderResult reference = renderer.render(scene.camera, many);
  double sum = 0.0;
  int lit = 0;
  for (std::size_t k = 0; k < r.rgba.size(); k += 4) {
    const auto y = [&](const std::vector<float>& v) { return 0.2126 * v[k] + 0.7152 * v[k + 1] + 0.0722 * v[k + 2]; };
    if (y(reference.rgba) < 1e-3) continue;
    const double e = (y(r.rgba) - y(reference.rgba)) / y(reference.rgba);
    sum += e * e;
    ++lit;
  }
  const double rms = std::sqrt(sum / lit);
  std::printf("%d samples, estimate %.3f; actual RMS relative error %.3f over %d lit pixels\n", report.samples,
              report.noise, rms, lit);
  EXPECT_TRUE(report.noise_reached);
  EXPECT_GT(lit, 50);
  EXPECT_LT(rms, 0.2);
}

TEST(ProgressEstimate, IsWithinAFactorTwoAfterTenPercent) {
  struct Render {
    double start_seconds;  // before the first report with work done
    double work_seconds;   // the even work after it
    double first_fraction;
  };
  for (const Render& r : {Render{11.5, 1.0, 0.04}, Render{0.0, 10.0, 0.01}, Render{0.3, 60.0, 0.05}}) {
    sol::programs::ProgressEstimate estimate;
    EXPECT_FALSE(estimate.report(0.0, 0.0));  // nothing done: no estimate
    const double end = r.start_seconds + r.work_seconds;
    for (double f = r.first_fraction; f < 1.0; f += 0.02) {
      // The first band is done at start_seconds; the rest runs evenly from there.
      const double t = r.start_seconds + r.work_seconds * (f - r.first_fraction) / (1.0 - r.first_fraction);
      const std::optional<double> left = estimate.report(t, f);
      ASSERT_TRUE(left);
      const double truth = end - t;
      if (f >= 0.1 && f <= 0.98) {
        EXPECT_LE(*left, 2.0 * truth) << "at " << f << " of a render starting " << r.start_seconds << " s late";
        EXPECT_GE(*left, 0.5 * truth) << "at " << f << " of a render starting " << r.start_seconds << " s late";
      }
    }
    EXPECT_EQ(estimate.report(end, 1.0), 0.0);
  }
  // A kernel built before the first tile: the renderer reports 0 again when
  // the work begins (MarchRenderer::render), and the first estimate counts
  // from there, not from the build (which made 1.5 s of work say 164 s).
  sol::programs::ProgressEstimate estimate;
  EXPECT_FALSE(estimate.report(0.0, 0.0));
  EXPECT_FALSE(estimate.report(30.0, 0.0));  // built
  const std::optional<double> first = estimate.report(30.1, 0.1);  // the first tile
  ASSERT_TRUE(first);
  EXPECT_NEAR(*first, 0.9, 1e-9);
}

// The presenters' frame figures (solview and solxr --stats): the mean and
// nearest-rank 99th percentile worked out by hand, intervals only where a
// frame had a predecessor, and a frame missed when work plus recording
// exceed its period (equal fits).
TEST(FrameStats, MeanPercentileAndMissedFramesByHand) {
  // Nearest rank: of 1..100 the 99th is 99, of 1..10 it is 10 (ceil(9.9) = 10), of one value that value.
  std::vector<double> hundred(100);
  for (int k = 0; k < 100; ++k) hundred[static_cast<std::size_t>(k)] = 100 - k;
  EXPECT_EQ(sol::programs::percentile(hundred, 99.0), 99.0);
  EXPECT_EQ(sol::programs::percentile({3, 1, 2, 10, 4, 5, 6, 7, 8, 9}, 99.0), 10.0);
  EXPECT_EQ(sol::programs::percentile({7.5}, 99.0), 7.5);
  EXPECT_EQ(sol::programs::percentile({}, 99.0), 0.0);
  EXPECT_EQ(sol::programs::percentile({4, 1, 3, 2}, 50.0), 2.0);

  sol::programs::FrameStats stats;
  stats.add(std::nullopt, 9.0, 1.0, 11.0);  // the first frame: no interval; 10 <= 11 fits
  stats.add(10.0, 10.0, 1.0, 11.0);         // 11 = 11: fits
  stats.add(12.0, 11.0, 0.5, 11.0);         // 11.5 > 11: missed
  stats.add(std::nullopt, 2.0, 0.5, 11.0);  // after a pause
  stats.add(14.0, 3.0, 0.0, 2.0);           // 3 > 2: missed
  EXPECT_EQ(stats.frames(), 5);
  EXPECT_EQ(stats.intervals(), 3);
  EXPECT_DOUBLE_EQ(stats.mean_interval_ms(), 12.0);
  EXPECT_EQ(stats.p99_interval_ms(), 14.0);
  EXPECT_DOUBLE_EQ(stats.mean_work_ms(), 7.0);
  EXPECT_DOUBLE_EQ(stats.mean_record_ms(), 0.6);
  EXPECT_EQ(stats.missed(), 2);
  EXPECT_EQ(stats.summary("stereo"), "stereo frames: 5, mean 12.000 ms, p99 14.000 ms, missed 2");
  EXPECT_EQ(sol::programs::FrameStats().summary("mono"), "mono frames: 0, mean 0.000 ms, p99 0.000 ms, missed 0");
}

// The adaptive render scale (solview --target-fps, solxr's display period)
// on a frame whose time goes with its pixels, K · scale² ms: it settles
// where the frame fits the target, aimed 10 % below (K s² <= target within
// the 5 % dead band, so s² within [target / 1.1 / K · 0.95², target / 1.1 / K · 1.05²]),
// holds there, drops at once after a frame over twice the target, and stays
// within [min_scale, 1].
TEST(AdaptiveScale, SettlesWhereTheFrameFitsTheTarget) {
  const double k = 40.0, target = 20.0;
  sol::programs::AdaptiveScale adaptive(target, 0.1);
  double scale = 1.0;
  for (long frame = 0; frame < 200; ++frame) scale = adaptive.next(scale, frame, k * scale * scale);
  const double settled = std::sqrt(target / 1.1 / k);
  EXPECT_GE(scale, settled * 0.95);
  EXPECT_LE(scale, settled * 1.05);
  EXPECT_LE(k * scale * scale, target);
  // A frame of five times the target (a heavier view) moves the scale at once, not at the next 8th frame.
  const double before = scale;
  scale = adaptive.next(scale, 201, 5.0 * target);
  EXPECT_LT(scale, before);
  // Never below the floor, never above 1.
  sol::programs::AdaptiveScale floor(1.0, 0.25);
  double s = 1.0;
  for (long frame = 0; frame < 100; ++frame) s = floor.next(s, frame, 1000.0);
  EXPECT_EQ(s, 0.25);
  sol::programs::AdaptiveScale ceiling(100.0, 0.25);
  s = 0.5;
  for (long frame = 0; frame < 100; ++frame) s = ceiling.next(s, frame, 1.0);
  EXPECT_EQ(s, 1.0);
}

namespace {

// The sRGB encoding's inverse (IEC 61966-2-1), written out.
double srgb_to_linear(double e) { return e <= 0.04045 ? e / 12.92 : std::pow((e + 0.055) / 1.055, 2.4); }

}  // namespace

TEST(TextureFile, AnEightBitFileIsDecodedToLinearAlbedos) {
  // A 3 × 2 PNG of 8-bit values written by OpenImageIO directly (grey in one
  // texel, colours in the others, an alpha channel that the texture drops):
  // read back as sRGB decoded to linear, each value the inverse curve of
  // its byte over 255.
  const fs::path dir = fresh_directory("texture");
  const std::string path = (dir / "t.png").string();
  const std::vector<std::uint8_t> bytes = {0, 0, 0, 255,      255, 255, 255, 255, 128, 64, 32, 10,
                                           10, 200, 90, 255,  1, 2, 3, 0,         250, 128, 0, 255};
  {
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out);
    OIIO::ImageSpec spec(3, 2, 4, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:UnassociatedAlpha", 1);  // the bytes as given, not divided by their alpha
    ASSERT_TRUE(out->open(path, spec));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, bytes.data()));
    out->close();
  }
  const sol::Texture t = sol::programs::read_texture_file(path);
  ASSERT_EQ(t.width, 3);
  ASSERT_EQ(t.height, 2);
  ASSERT_EQ(t.rgb.size(), 18u);
  for (std::size_t k = 0; k < 6; ++k) {
    for (std::size_t c = 0; c < 3; ++c) EXPECT_NEAR(t.rgb[3 * k + c], srgb_to_linear(bytes[4 * k + c] / 255.0), 1e-6) << k;
  }
  fs::remove_all(dir);
}

TEST(TextureFile, AFloatFileIsLinearAndCutToAnAlbedo) {
  // An EXR's values are linear already: taken as they are, those outside
  // [0, 1] cut to it; a grey (one-channel) image spreads to R, G, B.
  const fs::path dir = fresh_directory("texture-float");
  const std::string path = (dir / "t.exr").string();
  const std::vector<float> values = {0.25f, 2.0f, -1.0f, 0.5f};
  {
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out);
    ASSERT_TRUE(out->open(path, OIIO::ImageSpec(2, 2, 1, OIIO::TypeDesc::FLOAT)));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, values.data()));
    out->close();
  }
  const sol::Texture t = sol::programs::read_texture_file(path);
  const float want[] = {0.25f, 1.0f, 0.0f, 0.5f};
  for (std::size_t k = 0; k < 4; ++k) {
    for (std::size_t c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(t.rgb[3 * k + c], want[k]) << k;
  }
  try {
    sol::programs::read_texture_file((dir / "missing.png").string());
    ADD_FAILURE() << "a missing file read";
  } catch (const sol::InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("missing.png"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}
