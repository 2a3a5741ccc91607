// solrender: renders a Sol scene headless to an image file (any format
// OpenImageIO writes) and optionally its AOVs to an EXR.
//
//   solrender --scene plane -o plane.png
//   solrender --scene my.json -o out.exr --aov aov.exr --width 256 --height 256
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <optional>
#include <sstream>
#include <span>
#include <string>
#include <thread>
#include <utility>
#include <cerrno>
#include <cstring>
#include <csignal>
#include <spawn.h>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

#include <nlohmann/json.hpp>
#include <sol/sol.hpp>

#include "command_line.hpp"
#include "image_file.hpp"
#include "output_file.hpp"
#include "progress.hpp"
#include "renderers.hpp"
#include "sampling.hpp"
#include "srgb.hpp"

namespace {

// The AOV file's channels, in interleave_aovs' order.
const std::vector<std::string> kAovChannels = {"object",     "distance",   "Px",         "Py",       "Pz",
                                                "steps",      "out_of_steps", "albedo.R", "albedo.G", "albedo.B",
                                                "emission.R", "emission.G", "emission.B", "N.X",      "N.Y",
                                                "N.Z"};

// Interleaves the AOV planes into kAovChannels' order.
std::vector<float> interleave_aovs(const sol::RenderResult& r) {
  const std::size_t n = r.object.size(), c = kAovChannels.size();
  std::vector<float> out(c * n);
  for (std::size_t k = 0; k < n; ++k) {
    out[c * k + 0] = r.object[k];
    out[c * k + 1] = r.distance[k];
    out[c * k + 2] = r.px[k];
    out[c * k + 3] = r.py[k];
    out[c * k + 4] = r.pz[k];
    out[c * k + 5] = r.steps[k];
    out[c * k + 6] = r.out_of_steps[k];
    for (std::size_t i = 0; i < 3; ++i) {
      out[c * k + 7 + i] = r.albedo[3 * k + i];
      out[c * k + 10 + i] = r.emission[3 * k + i];
      out[c * k + 13 + i] = r.normal[3 * k + i];
    }
  }
  return out;
}

// A red/cyan anaglyph from a side-by-side stereo render: red from the left
// eye, green and blue from the right (linear colour); the AOVs the left eye's.
sol::RenderResult to_anaglyph(const sol::RenderResult& both) {
  const int w = both.width / 2, h = both.height;
  sol::RenderResult r;
  r.width = w;
  r.height = h;
  const std::size_t n = static_cast<std::size_t>(w) * h;
  r.rgba.resize(4 * n);
  const bool aovs = !both.object.empty();  // (rendered with RenderOptions::aovs)
  if (aovs) {
    for (auto* plane : {&r.object, &r.distance, &r.px, &r.py, &r.pz, &r.steps, &r.out_of_steps}) plane->resize(n);
    for (auto* plane : {&r.albedo, &r.emission, &r.normal}) plane->resize(3 * n);
  }
  r.rays_out_of_steps = both.rays_out_of_steps;
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * w + i;
      const std::size_t left = static_cast<std::size_t>(j) * 2 * w + i, right = left + w;
      r.rgba[4 * k + 0] = both.rgba[4 * left + 0];
      r.rgba[4 * k + 1] = both.rgba[4 * right + 1];
      r.rgba[4 * k + 2] = both.rgba[4 * right + 2];
      r.rgba[4 * k + 3] = 1.0f;
      if (!aovs) continue;
      r.object[k] = both.object[left];
      r.distance[k] = both.distance[left];
      r.px[k] = both.px[left];
      r.py[k] = both.py[left];
      r.pz[k] = both.pz[left];
      r.steps[k] = both.steps[left];
      r.out_of_steps[k] = both.out_of_steps[left] + both.out_of_steps[right];  // (both eyes' rays make the pixel)
      for (std::size_t c = 0; c < 3; ++c) {
        r.albedo[3 * k + c] = both.albedo[3 * left + c];
        r.emission[3 * k + c] = both.emission[3 * left + c];
        r.normal[3 * k + c] = both.normal[3 * left + c];
      }
    }
  }
  return r;
}

// -o for a film: where its one printf frame number (%d, or zero-padded as
// %06d: a 0 and at most two width digits; a width without the 0 pads with
// spaces, names no one wants) ends, the 'd'; none when there is not
// exactly one such conversion or there is another (%% is a percent sign).
std::optional<std::size_t> frame_number_end(const std::string& pattern) {
  std::optional<std::size_t> found;
  for (std::size_t i = 0; i < pattern.size(); ++i) {
    if (pattern[i] != '%') continue;
    if (i + 1 < pattern.size() && pattern[i + 1] == '%') {
      ++i;
      continue;
    }
    std::size_t j = i + 1;
    const bool zero = j < pattern.size() && pattern[j] == '0';
    if (zero) ++j;
    const std::size_t width_start = j;
    while (j < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[j]))) ++j;
    const std::size_t width = j - width_start;
    if (j >= pattern.size() || pattern[j] != 'd' || width > 2 || (width > 0 && !zero) || (zero && width == 0) || found) {
      return std::nullopt;
    }
    found = j;
    i = j;
  }
  return found;
}

// The pattern with frame number k (frame_number_end found its conversion).
std::string frame_name(const std::string& pattern, long k) {
  std::vector<char> format(pattern.begin(), pattern.end());
  format.insert(format.begin() + static_cast<std::ptrdiff_t>(*frame_number_end(pattern)), 'l');  // %06d -> %06ld
  format.push_back('\0');
  const int length = std::snprintf(nullptr, 0, format.data(), k);  // the whole name, however wide the number
  std::vector<char> out(static_cast<std::size_t>(std::max(length, 0)) + 1);
  std::snprintf(out.data(), out.size(), format.data(), k);
  return out.data();
}

// An executable on PATH, or empty.
std::string find_program(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/bin:/bin";
  std::size_t start = 0;
  while (start <= dirs.size()) {
    const std::size_t end = std::min(dirs.find(':', start), dirs.size());
    const std::filesystem::path candidate = std::filesystem::path(dirs.substr(start, end - start)) / name;
    std::error_code ec;
    if (std::filesystem::is_regular_file(candidate, ec) && access(candidate.c_str(), X_OK) == 0) return candidate.string();
    start = end + 1;
  }
  return {};
}

// ffmpeg's container for a --video file name (.mp4, .mkv, .mov), or none.
const char* video_format(const std::string& video) {
  std::string ext = std::filesystem::path(video).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const std::pair<const char*, const char*> formats[] = {{".mp4", "mp4"}, {".mkv", "matroska"}, {".mov", "mov"}};
  for (const auto& [e, f] : formats) {
    if (ext == e) return f;
  }
  return nullptr;
}

// Encodes the film's frames first_frame..end_frame-1 (the -o pattern) into
// `video` with ffmpeg: H.264 in yuv420p (sizes padded to even numbers),
// written to a temporary and moved onto `video` when ffmpeg succeeds. With
// `tty`, a progress line (frames encoded, percent, time left) from
// ffmpeg's own progress reports (-progress on a pipe).
void encode_video(const std::string& ffmpeg, const std::string& pattern, long first_frame, long end_frame, double fps,
                  const std::string& video, bool tty) {
  const char* format = video_format(video);  // checked before the first frame (film_of)
  sol::programs::OutputFile out(video);
  const std::string rate = std::to_string(fps), start = std::to_string(first_frame);
  const long frames = end_frame - first_frame;
  const std::string count = std::to_string(frames);  // (not the frames beyond --frames)
  std::vector<std::string> args = {ffmpeg, "-y", "-loglevel", "error", "-nostats", "-progress", "pipe:1", "-framerate",
                                   rate, "-start_number", start, "-i", pattern, "-frames:v", count, "-c:v", "libx264",
                                   "-pix_fmt", "yuv420p", "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-f", format, out.path()};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  int report[2] = {-1, -1};
  if (pipe2(report, O_CLOEXEC) != 0) throw std::runtime_error("--video: cannot make a pipe for ffmpeg's progress");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, report[1], STDOUT_FILENO);  // (dup2 clears close-on-exec)
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, ffmpeg.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(report[1]);
  if (spawned != 0) {
    ::close(report[0]);
    throw std::runtime_error("--video: cannot run " + ffmpeg);
  }
  const sol::programs::ChildProcess listed(pid);  // a signal ends it with us
  // ffmpeg's reports: key=value lines, "frame=N" among them, until it ends.
  std::FILE* reports = fdopen(report[0], "r");
  if (reports == nullptr) ::close(report[0]);
  sol::programs::ProgressTimer timer;
  char line[256];
  bool shown = false;
  while (reports != nullptr && std::fgets(line, sizeof line, reports) != nullptr) {
    long done = 0;
    if (!tty || std::sscanf(line, "frame=%ld", &done) != 1 || frames <= 0) continue;
    const double fraction = std::clamp(static_cast<double>(done) / static_cast<double>(frames), 0.0, 1.0);
    const std::optional<double> left = timer.report(fraction);
    std::fprintf(stderr, "\rsolrender: encoding %s: %ld of %ld frames (%.0f %%)", video.c_str(), done, frames, 100.0 * fraction);
    if (left && fraction < 1.0) std::fprintf(stderr, ", about %.0f s left", *left);
    std::fprintf(stderr, "      ");
    shown = true;
  }
  if (reports != nullptr) std::fclose(reports);
  if (shown) std::fprintf(stderr, "\n");
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) throw std::runtime_error("--video: ffmpeg failed to encode " + video);
  out.commit();
  std::fprintf(stderr, "solrender: encoded %s with ffmpeg\n", video.c_str());
}

// --video-only: ffmpeg reads the frames on its standard input as they
// render (raw 8-bit sRGB RGBA, width x height at the film's rate) and
// encodes them as encode_video does into the video's temporary; no frame
// file is written or read. finish() closes the pipe, waits for ffmpeg and
// commits the video; given up unfinished (an error, a signal), ffmpeg is
// stopped and the temporary removed.
class VideoPipe {
 public:
  VideoPipe(const std::string& ffmpeg, const std::string& video, int width, int height, double fps,
            const sol::Display& display)
      : m_out(video), m_video(video), m_tone(static_cast<int>(display.tone)), m_scale(display.scale()) {
    std::signal(SIGPIPE, SIG_IGN);  // a dead ffmpeg is a failed write (EPIPE), not the end of solrender
    int fds[2] = {-1, -1};
    if (pipe(fds) != 0) throw std::runtime_error("--video: cannot make a pipe to ffmpeg");
    const std::string size = std::to_string(width) + "x" + std::to_string(height);
    std::vector<std::string> args = {ffmpeg, "-y", "-loglevel", "error", "-f", "rawvideo", "-pix_fmt", "rgba",
                                     "-s", size, "-framerate", std::to_string(fps), "-i", "-", "-c:v", "libx264",
                                     "-pix_fmt", "yuv420p", "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-f",
                                     video_format(video), m_out.path()};
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, fds[0], STDIN_FILENO);
    posix_spawn_file_actions_addclose(&actions, fds[1]);
    const int spawned = posix_spawn(&m_pid, ffmpeg.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    close(fds[0]);
    if (spawned != 0) {
      close(fds[1]);
      throw std::runtime_error("--video: cannot run " + ffmpeg);
    }
    m_fd = fds[1];
    m_listed.emplace(m_pid);  // a signal ends it with us
  }
  ~VideoPipe() {
    if (m_fd >= 0) close(m_fd);
    if (m_pid > 0) {
      kill(m_pid, SIGTERM);
      int status = 0;
      waitpid(m_pid, &status, 0);
    }
  }
  VideoPipe(const VideoPipe&) = delete;
  VideoPipe& operator=(const VideoPipe&) = delete;

  // The frame's next rows, converted to bytes as the image files are (the display's exposure and curve, sRGB) and written.
  void write_rows(std::span<const float> rgba) {
    m_bytes.resize(rgba.size());
    for (std::size_t k = 0; k < rgba.size(); ++k) {
      const float v = std::isfinite(rgba[k]) ? rgba[k] : 0.0f;
      m_bytes[k] = k % 4 == 3 ? static_cast<std::uint8_t>(255) : sol::programs::display_byte(v, m_tone, m_scale);
    }
    const auto* at = m_bytes.data();
    std::size_t left = m_bytes.size();
    while (left > 0) {
      const ssize_t n = write(m_fd, at, left);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) throw std::runtime_error("--video: ffmpeg stopped reading the frames (" + m_video + ")");
      at += n;
      left -= static_cast<std::size_t>(n);
    }
  }

  void finish() {
    close(m_fd);
    m_fd = -1;
    int status = 0;
    waitpid(m_pid, &status, 0);
    m_pid = 0;
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) throw std::runtime_error("--video: ffmpeg failed to encode " + m_video);
    m_out.commit();
    std::fprintf(stderr, "solrender: encoded %s with ffmpeg, frames piped as they rendered\n", m_video.c_str());
  }

 private:
  sol::programs::OutputFile m_out;
  std::string m_video;
  int m_tone;      // the display's curve (sol/tone.h) ...
  double m_scale;  // ... and exposure scale
  pid_t m_pid = 0;
  std::optional<sol::programs::ChildProcess> m_listed;
  int m_fd = -1;
  std::vector<std::uint8_t> m_bytes;
};

// Renders a camera's image (both eyes, an anaglyph, as the options say).
// With a sink (and no anaglyph, which is made from the whole stereo image)
// the colour goes into it band by band as the renderer reads it back
// (RenderOptions::rows) and the result's colour stays empty; else the
// result holds it.
using RowSink = std::function<void(int first_row, int rows, std::span<const float> rgba)>;
using Render = std::function<sol::RenderResult(const sol::Camera&, const RowSink*)>;

// The colour of `r` into `sink` where the render did not hand it over.
void hand_over(const RowSink& sink, const sol::RenderResult& r) {
  if (!r.rgba.empty()) sink(0, r.height, r.rgba);
}

// An image file's sink: its rows into the writer.
RowSink into(sol::programs::ImageWriter& writer) {
  return [&writer](int first, int rows, std::span<const float> rgba) { writer.write_rows(first, rows, rgba); };
}

bool is_cpu(const sol::Renderer& renderer) { return dynamic_cast<const sol::CpuRenderer*>(&renderer) != nullptr; }

// What the command line asks for.
struct Options {
  std::string scene = "plane", output, aov, device = "auto", path_file, frames, video, projection, transport = "direct";
  std::string stereo_mode;  // empty: mono
  double fps = 24.0, ipd = 0.064;
  std::optional<double> fisheye_fov;
  std::optional<double> time_limit, noise_target;  // render in batches until either (sampling.hpp)
  std::optional<double> exposure;  // stops; none: the scene's
  std::string tone;                // empty: the scene's
  sol::cli::IntegratorOptions flow;
  sol::cli::SceneOverrides overrides;
  bool print_scene = false, progress = false, overwrite = false, video_only = false, denoise = false;
  int width = 512, height = 512, spp = 0;  // spp 0: the scene's "samples"
  int seed = 0;                            // the path tracer's
  unsigned threads = 0;

  bool stereo() const { return !stereo_mode.empty(); }
  bool anaglyph() const { return stereo_mode == "anaglyph"; }
};

// The written image's width: both eyes side by side in stereo, one anaglyph.
int image_width(const Options& o) { return o.width * (o.stereo() && !o.anaglyph() ? 2 : 1); }

// The options, their help and the footer.
void declare(sol::cli::CommandLine& cl, Options& o) {
  cl.add_text("--scene", o.scene, "NAME|FILE", "a preset (" + sol::cli::preset_list() + ") or a JSON scene file (default plane)");
  cl.add_text("-o,--output", o.output, "OUT", "image file; the format follows the extension (png, exr, jpg, tif, ...)");
  cl.add_text("--aov", o.aov, "FILE.exr", "also write float channels object, distance, Px, Py, Pz, steps, out_of_steps, albedo.RGB, emission.RGB, N.XYZ");
  cl.add_integer("--width", o.width, 1, 16384, "W", "image width in pixels, 1..16384 (default 512)");
  cl.add_integer("--height", o.height, 1, 16384, "H", "image height in pixels, 1..16384 (default 512)");
  o.overrides.add_to(cl, "camera");
  cl.add_choice("--projection", o.projection, {"perspective", "equirectangular", "fisheye"},
                "how pixels map to directions: perspective (the scene's fov), equirectangular (360 x 180 degrees, "
                "width = 2 x height) or fisheye (equidistant, --fisheye-fov across the image circle)");
  cl.add_number("--fisheye-fov", o.fisheye_fov, "DEG", "a fisheye's angle across its image circle, (0, 360] (default 180: a dome)",
                sol::cli::in_range(1e-3, 360.0));
  cl.add_integer("--spp", o.spp, 1, 4096, "N",
                 "samples per pixel, 1..4096 (default: the scene's \"samples\", 1 unless it says): anti-aliasing, "
                 "the colour the mean of N rays through the pixel (sol::pixel_sample 0..N-1, an evenly spread "
                 "sequence; sample 0 is the centre); the AOVs stay the centre's");
  cl.add_number("--exposure", o.exposure, "STOPS",
                "scale the colour of 8-bit images and videos by 2^STOPS before the tone curve, [-20, 20] (default: "
                "the scene's \"exposure\", 0); float images (EXR) stay linear",
                sol::cli::in_range(-sol::Display::kMaxExposure, sol::Display::kMaxExposure));
  std::vector<std::string> tones;
#define SOL_TONE_OPTION(Enum, code_name, code, name) tones.emplace_back(name);
  SOL_TONE_CURVES(SOL_TONE_OPTION)
#undef SOL_TONE_OPTION
  cl.add_choice("--tone", o.tone, tones,
                "the tone curve of 8-bit images and videos: clamp (the colour cut at white) or aces (a filmic "
                "curve that rolls highlights off; docs/scene-format.md) (default: the scene's \"tone\", clamp)");
  cl.add_number("--time-limit", o.time_limit, "S",
                "render samples in batches (pairs of equal size, each twice the last) until the next would pass S "
                "seconds, at least --spp (or the scene's samples) and at most 4096 per pixel",
                sol::cli::in_range(1e-3, 1e6));
  cl.add_number("--noise-target", o.noise_target, "E",
                "render samples in batches until the estimated relative error per pixel (from the difference of two "
                "independent halves of the samples, over each pixel's 3x3 neighbourhood) is at most E in 99 % of "
                "the pixels, e.g. 0.05; with --time-limit whichever comes first",
                sol::cli::in_range(1e-4, 10.0));
  cl.add_choice("--device", o.device, {"auto", "vulkan", "cpu"},
                "where to render: auto takes Vulkan (a GPU, else lavapipe) when available and the CPU renderer "
                "otherwise (default auto)");
  cl.add_choice("--transport", o.transport, {"direct", "path"},
                "how light reaches the eye: direct (each hit lit by the lights, with ambient light, mirrors and "
                "emission; the default) or path (path tracing: diffuse interreflection, glowing objects, mirrors, the "
                "lights by next-event estimation, no ambient light; each of --spp samples one path, on the kernel or "
                "the CPU renderer; docs/lighting.md)");
  cl.add_integer("--seed", o.seed, 0, 2147483647, "N",
                 "the path tracer's random seed, 0..2^31-1 (default 0): the same seed gives the same image");
  o.flow.add_to(cl);
  cl.add_optional_choice("--stereo", o.stereo_mode, {"side-by-side", "anaglyph"}, "side-by-side",
                         "both eyes: side by side (the default; image width 2 W) or as a red/cyan anaglyph (width W: "
                         "red from the left eye, green and blue from the right; the AOVs the left eye's); with "
                         "--projection equirectangular an omnidirectional stereo panorama (each column's eyes "
                         "on its own right vector)");
  cl.add_number("--ipd", o.ipd, "D", "eye separation in Sol units for --stereo, [0, 10] (default 0.064)",
                sol::cli::in_range(0.0, 10.0));
  cl.add_integer("--threads", o.threads, 1, 1024, "N", "CPU threads for --device cpu (default: all)");
  cl.add_flag("--denoise", o.denoise,
              "denoise the image (an edge-avoiding filter guided by the albedo, normal and distance, on the renderer's "
              "device; docs/lighting.md, \"Denoising\"): for path-traced stills and films of few samples");
  cl.add_flag("--print-scene", o.print_scene, "print the effective scene as JSON and exit");
  cl.add_text("--path", o.path_file, "FILE",
              "render a film along a camera path (JSON: a start and walk/turn/hold segments, docs/films.md): one "
              "image per frame, -o a pattern with a frame number (out/frame-%06d.png); frames already written are "
              "skipped, so a stopped run goes on where it was");
  cl.add_number("--fps", o.fps, "F", "frames per second of --path, (0, 1000] (default 24)", sol::cli::in_range(1e-3, 1000.0));
  cl.add_text("--frames", o.frames, "A:B", "with --path: frames A to B-1 only (either may be left out; default all)");
  cl.add_text("--video", o.video, "FILE.mp4", "with --path: encode the frames with ffmpeg into FILE (.mp4, .mkv, .mov)");
  cl.add_flag("--video-only", o.video_only,
              "with --video: pipe each frame into ffmpeg as it renders and write no frame files (no -o; a stopped "
              "run leaves no video and starts again from the first frame)");
  cl.add_flag("--overwrite", o.overwrite,
              "with --path: render every frame of --frames again, replacing those there, and record these settings "
              "(without it, frames rendered with other settings are refused, not mixed in)");
  cl.add_flag("--progress", o.progress,
              "a progress line on stderr (percent, rays/s, time left; the default when stderr is a terminal)");
  cl.set_footer(
      "Camera options override the scene's. 8-bit formats get sRGB-encoded colours, float formats\n"
      "linear ones. On failure nothing is written and the exit status is non-zero (2 for bad usage).");
}

// The scene with the command line's camera, projection and samples.
sol::Scene scene_of(Options& o, const sol::cli::CommandLine& cl) {
  sol::Scene scene;
  try {
    scene = sol::cli::scene_argument(o.scene);
    o.overrides.apply(scene);
    if (o.projection == "perspective") scene.camera.projection = sol::Projection::Perspective;
    if (o.projection == "equirectangular") scene.camera.projection = sol::Projection::Equirectangular;
    if (o.projection == "fisheye") scene.camera.projection = sol::Projection::Fisheye;
    if (o.fisheye_fov) scene.camera.fisheye_fov = *o.fisheye_fov;
    if (scene.camera.projection != sol::Projection::Perspective) scene.camera.frustum.reset();
    if (o.exposure) scene.display.exposure = *o.exposure;
    if (!o.tone.empty()) scene.display.tone = *sol::tone_from_name(o.tone);
    sol::validate(scene);
  } catch (const std::exception& e) {
    cl.fail(e.what());
  }
  if (o.spp == 0) o.spp = scene.samples;
  scene.samples = o.spp;  // what --print-scene shows
  return scene;
}

// Refuses an image size, output or AOV file that cannot be written, before any work.
void check_outputs(const Options& o, const sol::Scene& scene, const sol::cli::CommandLine& cl) {
  if (scene.camera.projection == sol::Projection::Equirectangular && o.width != 2 * o.height) {
    cl.fail("an equirectangular image needs --width = 2 x --height (360 x 180 degrees), got " + std::to_string(o.width) +
            " x " + std::to_string(o.height));
  }
  if (o.video_only) {
    if (o.video.empty() || o.path_file.empty()) cl.fail("--video-only needs --path FILE and --video FILE");
    if (!o.output.empty()) cl.fail("--video-only writes no frame files: leave out -o " + o.output);
    if (!o.aov.empty()) cl.fail("--aov is not available with --path (one image per frame)");
    return;
  }
  if (o.output.empty()) cl.fail("no output file: give -o OUT (see solrender --help)");
  if (!sol::programs::can_write(o.output)) cl.fail(o.output + ": no image format for this file name extension");
  if (!o.aov.empty() && std::filesystem::path(o.aov).extension() != ".exr") cl.fail("--aov needs an .exr file name, got " + o.aov);
  for (const std::string& path : {o.output, o.aov}) {
    if (!path.empty() && std::filesystem::is_directory(path)) cl.fail(path + ": cannot write: it is a directory");
  }
  if (!o.aov.empty() && sol::programs::same_file(o.output, o.aov)) {
    cl.fail("--aov " + o.aov + " is the same file as -o " + o.output + ": give two files");
  }
  if (o.flow.rk4() && o.device == "cpu") cl.fail("--integrator rk4 needs the Vulkan kernel (--device vulkan or auto)");
}

// A descriptor closed when its owner goes (a lock held while it lives).
struct FileDescriptor {
  int fd = -1;
  FileDescriptor() = default;
  explicit FileDescriptor(int d) : fd(d) {}
  FileDescriptor(FileDescriptor&& other) noexcept : fd(std::exchange(other.fd, -1)) {}
  FileDescriptor& operator=(FileDescriptor&& other) noexcept {
    if (this != &other) {
      if (fd >= 0) ::close(fd);
      fd = std::exchange(other.fd, -1);
    }
    return *this;
  }
  ~FileDescriptor() {
    if (fd >= 0) ::close(fd);
  }
};

// A film: its camera path, the frames to render and the encoder.
struct Film {
  sol::CameraPath path;
  long first = 0, end = 0;  // frames first..end-1
  std::string ffmpeg;       // with --video
  std::string manifest;     // the settings' file beside the frames (film_manifest)
  // The frames of first..end-1 already there whole (decoded), which a
  // rerun skips; a frame file that does not decode is rendered again.
  std::vector<bool> done;
  // The manifest, open with a shared lock for as long as the film renders:
  // shards of this film share the folder, another film cannot take it
  // (check_film_folder).
  FileDescriptor manifest_lock;
};

// The film's manifest file: beside the frames, named as the pattern with
// its frame number replaced by "film" and the extension by .json
// (out/frame-%06d.png: out/frame-film.json).
std::string manifest_name(const std::string& pattern) {
  const std::size_t d = *frame_number_end(pattern);
  const std::size_t percent = pattern.rfind('%', d);
  std::filesystem::path name = pattern.substr(0, percent) + "film" + pattern.substr(d + 1);
  name.replace_extension(".json");
  return name.string();
}

// What makes the frames what they are, as JSON: the effective scene (the
// camera options applied), the path, the frame rate, the size, the
// samples, stereo and the integrator. The device and --frames are not in
// it: shards of one film on other machines write the same manifest.
std::string film_manifest(const Options& o, const sol::Scene& scene) {
  nlohmann::ordered_json m;
  m["solrender_film"] = 1;
  m["scene"] = nlohmann::ordered_json::parse(sol::to_json(scene));
  // (Read and checked by load_camera_path; a file swapped since is refused as it was.)
  sol::FileRefusal why;
  const std::optional<std::string> text = sol::read_regular_file(o.path_file, std::uintmax_t{64} << 20, &why);
  if (!text) throw std::runtime_error("--path " + o.path_file + ": " + why.text);
  m["path"] = nlohmann::ordered_json::parse(*text);
  m["fps"] = o.fps;
  m["width"] = o.width;
  m["height"] = o.height;
  m["spp"] = o.spp;
  m["stereo"] = o.stereo_mode.empty() ? "mono" : o.stereo_mode;
  m["ipd"] = o.stereo() ? o.ipd : 0.0;
  m["integrator"] = o.flow.rk4() ? "rk4 " + std::to_string(o.flow.rk_step) : "closed";
  if (o.transport == "path") m["transport"] = "path seed " + std::to_string(o.seed);
  return m.dump(2) + "\n";
}

// Which of the manifest's top-level fields differ between `was` and `now`.
std::string differing_fields(const std::string& was, const std::string& now) {
  const auto a = nlohmann::ordered_json::parse(was, nullptr, false), b = nlohmann::ordered_json::parse(now);
  if (a.is_discarded() || !a.is_object()) return "it is not a film manifest";
  std::string fields;
  for (const auto& [key, value] : b.items()) {
    if (!a.contains(key) || a[key] != value) fields += (fields.empty() ? "" : ", ") + key;
  }
  if (fields.empty()) return "its text differs";
  return fields + (fields.find(',') == std::string::npos ? " differs" : " differ");
}

// A film's frames are only ever one film's: the folder is made, and the
// manifest there must be these settings' (written if there is none);
// frames without one, or with another's, are refused unless --overwrite.
// Films started at once are told apart under an exclusive lock of the
// folder (flock), taken while the manifest is read and written; the film
// then holds a shared lock of its manifest while it renders, which shards
// of the same film share and which --overwrite (another film's frames to
// replace) must take alone. A run alone there also removes the temporaries
// a killed run left (.NAME.XXXXXX beside a frame). Frames already there
// count as done only where they decode whole (image_decodes).
void check_film_folder(const Options& o, const sol::Scene& scene, Film& film, const sol::cli::CommandLine& cl) {
  const std::filesystem::path folder = std::filesystem::path(frame_name(o.output, film.first)).parent_path();
  std::error_code ec;
  if (!folder.empty()) std::filesystem::create_directories(folder, ec);
  if (ec) cl.fail("-o " + o.output + ": cannot make the folder " + folder.string() + ": " + ec.message());
  const std::string where = folder.empty() ? "." : folder.string();
  const FileDescriptor folder_lock(::open(where.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
  if (folder_lock.fd < 0 || ::flock(folder_lock.fd, LOCK_EX) != 0) {
    cl.fail("-o " + o.output + ": cannot lock the folder " + where + ": " + std::strerror(errno));
  }
  film.manifest = manifest_name(o.output);
  std::string now;
  try {
    now = film_manifest(o, scene);
  } catch (const std::exception& e) {
    cl.fail(e.what());
  }
  sol::FileRefusal why;
  const std::optional<std::string> was = sol::read_regular_file(film.manifest, std::uintmax_t{16} << 20, &why);
  if (!was && why.kind != sol::FileRefusal::Kind::Missing) {
    cl.fail("-o " + o.output + ": " + film.manifest + " is not a film manifest (" + why.text + "); remove it, or give another -o");
  }
  // The manifest there, locked: none may be another film's running now where it is to be replaced.
  auto lock_manifest = [&](int how) {
    FileDescriptor m(::open(film.manifest.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC));
    if (m.fd < 0 || ::flock(m.fd, how | LOCK_NB) != 0) return FileDescriptor();
    return m;
  };
  if (was && *was != now) {
    if (!o.overwrite) {
      cl.fail("-o " + o.output + ": the frames there were rendered with other settings (" + film.manifest + ": " +
              differing_fields(*was, now) + "); --overwrite renders them again with these, or give another -o");
    }
    if (lock_manifest(LOCK_EX).fd < 0) {
      cl.fail("-o " + o.output + ": another solrender is rendering the film of " + film.manifest +
              " there now; --overwrite would mix its frames with these: wait for it, or give another -o");
    }
  }
  if (!was && !o.overwrite) {
    for (long k = film.first; k < film.end; ++k) {
      if (std::filesystem::exists(frame_name(o.output, k))) {
        cl.fail("-o " + o.output + ": " + frame_name(o.output, k) + " is there without a film manifest (" + film.manifest +
                "), so its settings are unknown; --overwrite renders the frames again, or give another -o");
      }
    }
  }
  if (!was || *was != now) {
    try {
      sol::programs::write_text_file(film.manifest, now);
    } catch (const std::exception& e) {
      cl.fail(e.what());
    }
  }
  // Alone here (no other run holds the manifest): the temporaries of a run
  // that was killed are removed. Then the shared lock, for the whole film.
  if (FileDescriptor alone = lock_manifest(LOCK_EX); alone.fd >= 0) {
    for (const auto& entry : std::filesystem::directory_iterator(where, ec)) {
      const std::string name = entry.path().filename().string();
      if (name.size() < 9 || name[0] != '.' || name[name.size() - 7] != '.') continue;
      const std::string frame = name.substr(1, name.size() - 8);  // .FRAME.XXXXXX
      for (long k = 0; k < film.end; ++k) {
        if (std::filesystem::path(frame_name(o.output, k)).filename() == frame) {
          std::filesystem::remove(entry.path(), ec);
          break;
        }
      }
    }
  }
  film.manifest_lock = lock_manifest(LOCK_SH);
  if (film.manifest_lock.fd < 0) cl.fail("-o " + o.output + ": cannot lock " + film.manifest + ": " + std::strerror(errno));
  // The frames already there whole; anything else in a frame's place is
  // rendered again (an empty or truncated file), or refused (a directory).
  film.done.assign(static_cast<std::size_t>(film.end - film.first), false);
  for (long k = film.first; k < film.end && !o.overwrite; ++k) {
    const std::string name = frame_name(o.output, k);
    if (std::filesystem::is_directory(name, ec)) cl.fail("-o " + o.output + ": " + name + " is a directory, not a frame");
    if (!std::filesystem::exists(name, ec)) continue;
    std::string broken;
    film.done[static_cast<std::size_t>(k - film.first)] = sol::programs::image_decodes(name, image_width(o), o.height, &broken);
    if (!film.done[static_cast<std::size_t>(k - film.first)]) {
      std::fprintf(stderr, "solrender: %s is not a whole frame (%s): rendering it again\n", name.c_str(), broken.c_str());
    }
  }
}

// The film --path asks for (none without it), its frames and video checked.
std::optional<Film> film_of(const Options& o, const sol::Scene& scene, const sol::cli::CommandLine& cl) {
  if (o.path_file.empty()) {
    if (!o.frames.empty() || !o.video.empty()) cl.fail(!o.frames.empty() ? "--frames needs --path FILE" : "--video needs --path FILE");
    return std::nullopt;
  }
  Film film;
  try {
    film.path = sol::load_camera_path(o.path_file);
  } catch (const std::exception& e) {
    cl.fail(e.what());
  }
  if (!o.aov.empty()) cl.fail("--aov is not available with --path (one image per frame)");
  if (!o.video_only && !frame_number_end(o.output)) {
    cl.fail("-o " + o.output + ": with --path the name needs one frame number, %d or zero-padded such as %06d (frame-%06d.png)");
  }
  const long count = film.path.frame_count(o.fps);
  film.end = count;
  if (!o.frames.empty()) {
    const auto colon = o.frames.find(':');
    if (colon == std::string::npos) cl.fail("--frames expects A:B (frames A to B-1; either may be left out), got '" + o.frames + "'");
    const std::string a = o.frames.substr(0, colon), b = o.frames.substr(colon + 1);
    if (!a.empty()) film.first = cl.integer(a, "--frames (first)", 0, count);
    if (!b.empty()) film.end = std::min(count, static_cast<long>(cl.integer(b, "--frames (end)", 0, 100000000)));
    if (film.first >= film.end) {
      cl.fail("--frames " + o.frames + ": no frames (the path has " + std::to_string(count) + " at " + std::to_string(o.fps) +
              " fps: 0.." + std::to_string(count - 1) + ")");
    }
  }
  // Every frame's camera before any is rendered: a path that leaves the
  // heights a camera may have fails now, naming the frame, not after
  // writing the frames before it.
  const std::optional<sol::Lattice> lattice = scene.lattice();
  for (long k = film.first; k < film.end; ++k) {
    try {
      sol::validate(film.path.at(static_cast<double>(k) / o.fps, scene.camera, lattice));
    } catch (const std::exception& e) {
      char when[96];
      std::snprintf(when, sizeof when, ": frame %ld (t = %g s): ", k, static_cast<double>(k) / o.fps);
      cl.fail("--path " + o.path_file + when + e.what());
    }
  }
  if (!o.video.empty()) {
    film.ffmpeg = find_program("ffmpeg");
    if (film.ffmpeg.empty()) {
      cl.fail("--video needs ffmpeg, which is not installed (Debian: apt install ffmpeg); without --video the frames "
              "are written and 'ffmpeg -framerate F -i PATTERN -pix_fmt yuv420p out.mp4' encodes them");
    }
    if (std::filesystem::is_directory(o.video)) cl.fail("--video " + o.video + ": it is a directory");
    if (!video_format(o.video)) cl.fail("--video " + o.video + ": give a .mp4, .mkv or .mov file");
    try {  // that the video can be written there, now rather than after the frames
      sol::programs::OutputFile probe(o.video);
    } catch (const std::exception& e) {
      cl.fail(std::string("--video ") + e.what());
    }
  }
  if (!o.video_only) check_film_folder(o, scene, film, cl);  // (no frames, no manifest with --video-only)
  return film;
}

// "peak memory N MB" (sol::process_memory: the most this process held at
// once), for the summary lines: a long render's memory must stay flat.
std::string peak_memory() {
  const double peak = sol::process_memory().peak_bytes;
  if (!(peak > 0.0)) return "peak memory unknown";
  char text[48];
  std::snprintf(text, sizeof text, "peak memory %.0f MB", peak / 1e6);
  return text;
}

// The progress line: finished fraction, rays per second so far, time left
// (sol::programs::ProgressEstimate: at the rate since work was first seen
// done); rewritten in place on a terminal, one line per 10% otherwise, the
// first at once.
class ProgressLine {
 public:
  ProgressLine(bool tty, double rays) : tty_(tty), rays_(rays) {}

  // A new image (a film's frame: `prefix` names it).
  void start(std::string prefix = {}) {
    prefix_ = std::move(prefix);
    last_tenth_ = -1;
    timer_ = {};
  }

  void report(double fraction) {
    const double seconds = timer_.seconds();
    const double rate = seconds > 0 ? fraction * rays_ / seconds : 0.0;
    const std::optional<double> left = timer_.report(fraction);
    if (!tty_) {
      const int tenth = static_cast<int>(fraction * 10.0 + 1e-9);
      if (tenth == last_tenth_) return;
      last_tenth_ = tenth;
    }
    // Nothing finished yet: no rate to go by, and no estimate pretends to one.
    char speed[48], remaining[48];
    if (left) {
      if (rate >= 1e5) std::snprintf(speed, sizeof speed, "%.2f M rays/s", rate * 1e-6);
      else std::snprintf(speed, sizeof speed, "%.0f rays/s", rate);
      std::snprintf(remaining, sizeof remaining, "%.1f s left", *left);
    } else {
      std::snprintf(speed, sizeof speed, "-- rays/s");
      std::snprintf(remaining, sizeof remaining, "time left unknown");
    }
    std::fprintf(stderr, "%ssolrender: %s%3.0f%%  %s  %s%s", tty_ ? "\r" : "", prefix_.c_str(), 100.0 * fraction, speed,
                 remaining, tty_ ? "   " : "\n");
  }

 private:
  bool tty_;
  double rays_;
  std::string prefix_;
  int last_tenth_ = -1;
  sol::programs::ProgressTimer timer_;
};

// The renderer, made once (a film's frames share it): the kernel, or the CPU.
std::unique_ptr<sol::Renderer> renderer_for(const Options& o, const sol::Scene& scene, const sol::cli::CommandLine& cl) {
  sol::programs::RendererChoice choice;
  choice.device = o.device == "vulkan" ? sol::programs::Device::Vulkan
                  : o.device == "cpu"  ? sol::programs::Device::Cpu
                                       : sol::programs::Device::Auto;
  choice.rk4 = o.flow.rk4();
  choice.rk4_step = o.flow.rk_step;
  choice.transport = o.transport == "path" ? sol::Transport::Path : sol::Transport::Direct;
#ifndef NDEBUG
  choice.validation = true;  // validation layers in debug builds
#endif
  if (choice.device == sol::programs::Device::Vulkan && !sol::programs::has_vulkan()) {
    cl.fail("--device vulkan: this solrender was built without Vulkan (SOL_BUILD_VULKAN=OFF)");
  }
  std::unique_ptr<sol::Renderer> renderer = sol::programs::make_renderer(
      choice, scene, [](const std::string& note) { std::fprintf(stderr, "solrender: %s\n", note.c_str()); });
  if (is_cpu(*renderer) && o.flow.rk4()) cl.fail("--integrator rk4 needs the Vulkan kernel");
  return renderer;
}

// --time-limit, --noise-target: the image in batches of samples
// (sampling.hpp), each a render of consecutive samples; the colour the
// mean of all of them, the AOVs the first batch's (the guides' albedo and
// emission the mean of all, as the colour). What was reached is said.
sol::RenderResult render_until(const Options& o, const sol::Camera& camera, const sol::RenderOptions& options,
                               const std::function<sol::RenderResult(const sol::Camera&, const sol::RenderOptions&)>& render,
                               ProgressLine& progress, bool tty, int& samples_done) {
  sol::programs::SamplingGoal goal;
  goal.seconds = o.time_limit;
  goal.noise = o.noise_target;
  goal.min_samples = o.spp;
  sol::programs::SamplingReport report;
  const auto batch = [&](int first, int count, bool aovs) {
    sol::RenderOptions these = options;
    these.first_sample = first;
    these.samples = count;
    these.aovs = aovs;
    these.guides = options.guides;  // (every batch's albedo and emission, joined as the colour)
    these.rows = nullptr;    // the colour is the batches' mean, handed over whole
    these.progress = nullptr;  // (progress: per pair, below)
    return render(camera, these);
  };
  const auto heard = [&](const sol::programs::SamplingReport& r) {
    if (!tty && !o.progress) return;
    if (o.time_limit) progress.report(std::min(1.0, r.seconds / *o.time_limit));
    std::fprintf(stderr, "%ssolrender: %d samples per pixel in %.1f s, estimated noise %.3g%s", tty ? "\r" : "", r.samples,
                 r.seconds, r.noise, tty ? "   " : "\n");
  };
  sol::RenderResult r = sol::programs::render_batches(batch, options.aovs, goal, report, heard);
  samples_done = report.samples;
  if (tty) std::fprintf(stderr, "\n");
  std::fprintf(stderr, "solrender: %d samples per pixel in %.2f s; estimated relative noise %.3g in 99 %% of the pixels%s\n",
               report.samples, report.seconds, report.noise,
               o.noise_target ? (report.noise_reached ? " (the target reached)" : " (the target not reached)") : "");
  return r;
}

// Says how much of an 8-bit picture the display cut at white, and what
// keeps it (the EXR is linear and keeps everything): nothing is clipped
// without a word.
void report_clipped(std::size_t clipped, double pixels, const sol::Display& display, const std::string& where) {
  if (clipped == 0 || pixels <= 0.0) return;
  std::fprintf(stderr,
               "solrender: note: %zu pixels (%.2g %%) are brighter than white under exposure %+g and tone %s and clip "
               "in %s; %s keeps their highlights\n",
               clipped, 100.0 * static_cast<double>(clipped) / pixels, display.exposure, sol::tone_name(display.tone),
               where.c_str(), display.tone == sol::Tone::Clamp ? "a lower --exposure or --tone aces" : "a lower --exposure");
}

// A film: frames first..end-1, each its own complete file; frames already
// there (complete: files appear only whole) are skipped, so a stopped run
// goes on where it was.
void render_film(const Options& o, const sol::Scene& scene, const Film& film, const Render& render, ProgressLine& progress,
                 bool tty, const std::string& where) {
  long rendered = 0, skipped = 0;
  const auto film_started = std::chrono::steady_clock::now();
  const std::optional<sol::Lattice> lattice = scene.lattice();
  long to_render = 0;
  for (long k = film.first; k < film.end; ++k) {
    to_render += o.video_only || o.overwrite || !film.done[static_cast<std::size_t>(k - film.first)];
  }
  // --video-only: every frame into ffmpeg as it renders, no frame files.
  std::optional<VideoPipe> video;
  if (o.video_only) video.emplace(film.ffmpeg, o.video, image_width(o), o.height, o.fps, scene.display);
  const RowSink to_video = [&video](int, int, std::span<const float> rgba) { video->write_rows(rgba); };
  // A frame whose file the worker still encodes (ImageWriter), finished
  // and committed after the next frame's render: frames are committed in turn.
  struct PendingFrame {
    std::unique_ptr<sol::programs::OutputFile> file;
    std::unique_ptr<sol::programs::ImageWriter> writer;
    sol::RenderResult result;
    std::string name;
  };
  std::optional<PendingFrame> pending;
  std::size_t clipped = 0;  // the frames' pixels cut at white
  const auto complete = [&clipped](PendingFrame& p) {
    hand_over(into(*p.writer), p.result);
    const std::size_t non_finite = p.writer->finish();
    clipped += p.writer->clipped();
    p.file->commit();
    if (non_finite > 0) std::fprintf(stderr, "solrender: warning: %zu non-finite values in %s written as 0\n", non_finite, p.name.c_str());
  };
  for (long k = film.first; k < film.end; ++k) {
    const std::string name = o.video_only ? std::string() : frame_name(o.output, k);
    if (!o.video_only && !o.overwrite && film.done[static_cast<std::size_t>(k - film.first)]) {
      ++skipped;
      continue;
    }
    const sol::Camera camera = film.path.at(static_cast<double>(k) / o.fps, scene.camera, lattice);
    // The film's time left at the frames' mean so far (none before the first is done).
    char film_left[48] = "";
    if (rendered > 0) {
      const double spent = std::chrono::duration<double>(std::chrono::steady_clock::now() - film_started).count();
      std::snprintf(film_left, sizeof film_left, ", film %.0f s left", spent / static_cast<double>(rendered) * static_cast<double>(to_render - rendered));
    }
    char prefix[160];
    std::snprintf(prefix, sizeof prefix, "frame %ld (%ld of %ld%s): ", k, rendered + 1, to_render, film_left);
    progress.start(prefix);
    if (video) {
      hand_over(to_video, render(camera, &to_video));
      if (tty) std::fprintf(stderr, "\r");
      ++rendered;
      continue;
    }
    auto file = std::make_unique<sol::programs::OutputFile>(name);
    auto writer = std::make_unique<sol::programs::ImageWriter>(
        *file, image_width(o), o.height, std::vector<std::string>{"R", "G", "B", "A"}, true, true, scene.display);
    const RowSink sink = into(*writer);
    sol::RenderResult r = render(camera, &sink);
    if (tty) std::fprintf(stderr, "\r");
    // The previous frame's file is finished only now: its last bands were
    // encoded while this frame rendered.
    if (pending) complete(*pending);
    pending = PendingFrame{std::move(file), std::move(writer), std::move(r), name};
    ++rendered;
  }
  if (pending) complete(*pending);
  if (video) video->finish();
  report_clipped(clipped, static_cast<double>(image_width(o)) * o.height * static_cast<double>(rendered), scene.display,
                 o.output + " (its frames)");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - film_started).count();
  std::fprintf(stderr, "solrender: path %s: frames %ld..%ld at %g fps on %s: %ld rendered in %.2f s, %ld already there, %s -> %s\n",
               o.path_file.c_str(), film.first, film.end - 1, o.fps, where.c_str(), rendered, seconds, skipped,
               peak_memory().c_str(), o.video_only ? o.video.c_str() : o.output.c_str());
  if (!o.video.empty() && !o.video_only) encode_video(film.ffmpeg, o.output, film.first, film.end, o.fps, o.video, tty || o.progress);
}

// One image and its AOVs: both files complete before either replaces what
// was there, so a failure leaves the previous files as they were.
void render_still(const Options& o, const sol::Scene& scene, const Render& render, bool tty, bool on_device,
                  std::string where, const int& samples_done) {
  const auto begin = std::chrono::steady_clock::now();
  sol::programs::OutputFile image(o.output);
  sol::programs::ImageWriter writer(image, image_width(o), o.height, {"R", "G", "B", "A"}, true, /*worker=*/true,
                                    scene.display);
  const RowSink sink = into(writer);
  const sol::RenderResult r = render(scene.camera, &sink);
  hand_over(sink, r);
  std::size_t non_finite = writer.finish();
  // (The render and the image file: the colour is encoded as it is read back.)
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  if (tty) std::fprintf(stderr, "\r");
  if (on_device) {
    char buf[64];
    std::snprintf(buf, sizeof buf, " (kernel %.1f ms)", r.device_ms);
    where += buf;
  }
  std::optional<sol::programs::OutputFile> aovs;
  if (!o.aov.empty()) {
    aovs.emplace(o.aov);
    non_finite += sol::programs::write_image(*aovs, r.width, r.height, kAovChannels, interleave_aovs(r), false);
  }
  image.commit();
  if (aovs) aovs->commit();
  if (non_finite > 0) {
    std::fprintf(stderr, "solrender: warning: %zu values were not finite and were written as 0 (a defect: please report "
                 "the scene and options)\n", non_finite);
  }
  report_clipped(writer.clipped(), static_cast<double>(r.width) * r.height, scene.display, o.output);
  // (With --time-limit or --noise-target the batches' count.)
  const int spp = samples_done > 0 ? samples_done : o.spp;
  const std::string samples = spp > 1 ? ", " + std::to_string(spp) + " samples per pixel" : "";
  std::fprintf(stderr, "solrender: %dx%d%s%s on %s: %.3f s, %.2f M rays/s, %s -> %s\n", r.width, r.height,
               o.anaglyph() ? " (anaglyph)" : (o.stereo() ? " (stereo)" : ""), samples.c_str(), where.c_str(), seconds,
               r.width * static_cast<double>(r.height) * (o.anaglyph() ? 2 : 1) * spp / seconds * 1e-6,
               peak_memory().c_str(), o.output.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  sol::programs::install_texture_reader();  // scene files' "texture" keys
  Options o;
  sol::cli::CommandLine cl("solrender", "[options] -o OUT",
                           "Renders what an observer inside Thurston's Sol geometry sees: every pixel follows a Sol "
                           "geodesic.");
  declare(cl, o);
  cl.parse(argc, argv);
  const sol::Scene scene = scene_of(o, cl);
  if (o.print_scene) {
    std::printf("%s\n", sol::to_json(scene).c_str());
    return 0;
  }
  check_outputs(o, scene, cl);
  const std::optional<Film> film = film_of(o, scene, cl);

  const bool tty = isatty(fileno(stderr));
  ProgressLine progress(tty, static_cast<double>(o.width) * (o.stereo() ? 2.0 : 1.0) * o.height * o.spp);
  // A signal in any phase leaves no temporary behind (and no output).
  sol::programs::install_signal_cleanup();
  try {
    const std::unique_ptr<sol::Renderer> renderer = renderer_for(o, scene, cl);
    std::string where = renderer->description();
    if (is_cpu(*renderer) && o.threads) where = "cpu (" + std::to_string(o.threads) + " threads)";
    sol::RenderOptions options;
    options.width = o.width;
    options.height = o.height;
    options.samples = o.spp;
    options.threads = o.threads;
    options.transport = o.transport == "path" ? sol::Transport::Path : sol::Transport::Direct;
    options.seed = static_cast<std::uint64_t>(o.seed);
    // The colour alone unless --aov or --denoise asks for more (less to read back and hold).
    options.aovs = !o.aov.empty() || o.denoise;
    options.guides = options.aovs;  // (the AOV file's albedo and normal; the denoiser's guides)
    options.max_dispatch_ms = 100.0;  // a device's dispatches in tiles of about 50 ms (a display's watchdog; progress)
    if (tty || o.progress) options.progress = [&](double fraction) { progress.report(fraction); };
    std::uint64_t out_of_steps = 0;  // every image's rays that ran out of march steps
    int samples_done = 0;            // per pixel, where batches decide (the last image's)
    const auto render_with = [&](const sol::Camera& camera, const sol::RenderOptions& these) {
      const sol::RenderResult both =
          o.stereo() ? renderer->render_stereo(camera, o.ipd, these) : renderer->render(camera, these);
      out_of_steps += both.rays_out_of_steps;
      return both;
    };
    // The image of all the samples, denoised (the eyes apart) and made an anaglyph where asked.
    const Render render = [&](const sol::Camera& camera, const RowSink* sink) {
      sol::RenderOptions these = options;
      if (sink != nullptr && !o.anaglyph() && !o.denoise) these.rows = *sink;
      sol::RenderResult r = !o.time_limit && !o.noise_target
                                ? render_with(camera, these)
                                : render_until(o, camera, these, render_with, progress, tty, samples_done);
      if (o.denoise) renderer->denoise(r, o.stereo() ? 2 : 1);
      return o.anaglyph() ? to_anaglyph(r) : r;
    };
    progress.start();
    if (film) {
      render_film(o, scene, *film, render, progress, tty, where);
    } else {
      render_still(o, scene, render, tty, !is_cpu(*renderer), where, samples_done);
    }
    if (out_of_steps > 0) {
      std::fprintf(stderr,
                   "solrender: warning: %llu rays ran out of march steps (max_steps %d) before they met an object or "
                   "max_distance, and were drawn as misses (shadow rays as unblocked): a larger --max-steps draws "
                   "them (the AOV channel out_of_steps shows where)\n",
                   static_cast<unsigned long long>(out_of_steps), scene.max_steps);
    }
  } catch (const std::exception& e) {
    if (tty) std::fprintf(stderr, "\n");
    cl.fail(e.what());
  }
  return 0;
}
