// solrender: renders a Sol scene headless to an image file (any format
// OpenImageIO writes) and optionally its AOVs to an EXR.
//
//   solrender --scene plane -o plane.png
//   solrender --scene my.json -o out.exr --aov aov.exr --width 256 --height 256
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <optional>
#include <string>
#include <thread>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

#include <sol/sol.hpp>

#include "command_line.hpp"
#include "image_file.hpp"
#include "output_file.hpp"
#include "renderers.hpp"

namespace {

// Interleaves the AOV planes into object, distance, Px, Py, Pz, steps.
std::vector<float> interleave_aovs(const sol::RenderResult& r) {
  const std::size_t n = r.object.size();
  std::vector<float> out(6 * n);
  for (std::size_t k = 0; k < n; ++k) {
    out[6 * k + 0] = r.object[k];
    out[6 * k + 1] = r.distance[k];
    out[6 * k + 2] = r.px[k];
    out[6 * k + 3] = r.py[k];
    out[6 * k + 4] = r.pz[k];
    out[6 * k + 5] = r.steps[k];
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
  for (auto* plane : {&r.object, &r.distance, &r.px, &r.py, &r.pz, &r.steps}) plane->resize(n);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * w + i;
      const std::size_t left = static_cast<std::size_t>(j) * 2 * w + i, right = left + w;
      r.rgba[4 * k + 0] = both.rgba[4 * left + 0];
      r.rgba[4 * k + 1] = both.rgba[4 * right + 1];
      r.rgba[4 * k + 2] = both.rgba[4 * right + 2];
      r.rgba[4 * k + 3] = 1.0f;
      r.object[k] = both.object[left];
      r.distance[k] = both.distance[left];
      r.px[k] = both.px[left];
      r.py[k] = both.py[left];
      r.pz[k] = both.pz[left];
      r.steps[k] = both.steps[left];
    }
  }
  return r;
}

// -o for a film: where its one printf frame number (%d, %06d: at most two
// width digits) ends, the 'd'; none when there is not exactly one such
// conversion or there is another (%% is a percent sign).
std::optional<std::size_t> frame_number_end(const std::string& pattern) {
  std::optional<std::size_t> found;
  for (std::size_t i = 0; i < pattern.size(); ++i) {
    if (pattern[i] != '%') continue;
    if (i + 1 < pattern.size() && pattern[i + 1] == '%') {
      ++i;
      continue;
    }
    std::size_t j = i + 1;
    while (j < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[j]))) ++j;
    if (j >= pattern.size() || pattern[j] != 'd' || j - i - 1 > 2 || found) return std::nullopt;
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
  std::vector<char> out(format.size() + 32);
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

// Encodes the film's frames (from first_frame on, the -o pattern) into
// `video` with ffmpeg: H.264 in yuv420p (sizes padded to even numbers),
// written to a temporary and moved onto `video` when ffmpeg succeeds.
void encode_video(const std::string& ffmpeg, const std::string& pattern, long first_frame, double fps,
                  const std::string& video) {
  std::string ext = std::filesystem::path(video).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const std::pair<const char*, const char*> formats[] = {{".mp4", "mp4"}, {".mkv", "matroska"}, {".mov", "mov"}};
  const char* format = nullptr;
  for (const auto& [e, f] : formats) {
    if (ext == e) format = f;
  }
  if (!format) throw std::runtime_error("--video " + video + ": give a .mp4, .mkv or .mov file");
  sol::programs::OutputFile out(video);
  const std::string rate = std::to_string(fps), start = std::to_string(first_frame);
  std::vector<std::string> args = {ffmpeg, "-y", "-loglevel", "error", "-framerate", rate, "-start_number", start,
                                   "-i", pattern, "-c:v", "libx264", "-pix_fmt", "yuv420p",
                                   "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-f", format, out.path()};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawn(&pid, ffmpeg.c_str(), nullptr, nullptr, argv.data(), environ) != 0) {
    throw std::runtime_error("--video: cannot run " + ffmpeg);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) throw std::runtime_error("--video: ffmpeg failed to encode " + video);
  out.commit();
  std::fprintf(stderr, "solrender: encoded %s with ffmpeg\n", video.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  std::string scene_arg = "plane", output, aov, device = "auto", path_file, frames, video;
  double fps = 24.0;
  std::string projection;
  std::optional<double> fisheye_fov;
  double ipd = 0.064;
  sol::cli::IntegratorOptions flow;
  bool print_scene = false, progress = false;
  std::string stereo_mode;  // empty: mono
  int width = 512, height = 512, spp = 0;  // 0: the scene's "samples"
  unsigned threads = 0;
  sol::cli::SceneOverrides o;
  sol::cli::CommandLine cl("solrender", "[options] -o OUT",
                           "Renders what an observer inside Thurston's Sol geometry sees: every pixel follows a Sol "
                           "geodesic.");
  cl.add_text("--scene", scene_arg, "NAME|FILE",
              "a preset (" + sol::cli::preset_list() + ") or a JSON scene file (default plane)");
  cl.add_text("-o,--output", output, "OUT", "image file; the format follows the extension (png, exr, jpg, tif, ...)");
  cl.add_text("--aov", aov, "FILE.exr", "also write float channels object, distance, Px, Py, Pz, steps");
  cl.add_integer("--width", width, 1, 16384, "W", "image width in pixels, 1..16384 (default 512)");
  cl.add_integer("--height", height, 1, 16384, "H", "image height in pixels, 1..16384 (default 512)");
  o.add_to(cl, "camera");
  cl.add_choice("--projection", projection, {"perspective", "equirectangular", "fisheye"},
                "how pixels map to directions: perspective (the scene's fov), equirectangular (360 x 180 degrees, "
                "width = 2 x height) or fisheye (equidistant, --fisheye-fov across the image circle)");
  cl.add_number("--fisheye-fov", fisheye_fov, "DEG", "a fisheye's angle across its image circle, (0, 360] (default 180: a dome)",
                sol::cli::in_range(1e-3, 360.0));
  cl.add_integer("--spp", spp, 1, 4096, "N",
                 "samples per pixel, 1..4096 (default: the scene's \"samples\", 1 unless it says): anti-aliasing, "
                 "the colour the mean of N rays through the pixel (an evenly spread sequence; sample 1 is the "
                 "centre); the AOVs stay the centre's");
  cl.add_choice("--device", device, {"auto", "vulkan", "cpu"},
                "where to render: auto takes Vulkan (a GPU, else lavapipe) when available and the CPU renderer "
                "otherwise (default auto)");
  flow.add_to(cl);
  cl.add_optional_choice("--stereo", stereo_mode, {"side-by-side", "anaglyph"}, "side-by-side",
                         "both eyes: side by side (the default; image width 2 W) or as a red/cyan anaglyph (width W: "
                         "red from the left eye, green and blue from the right; the AOVs the left eye's); with "
                         "--projection equirectangular an omnidirectional stereo panorama (each column's eyes "
                         "on its own right vector)");
  cl.add_number("--ipd", ipd, "D", "eye separation in Sol units for --stereo, [0, 10] (default 0.064)",
                sol::cli::in_range(0.0, 10.0));
  cl.add_integer("--threads", threads, 1, 1024, "N", "CPU threads for --device cpu (default: all)");
  cl.add_flag("--print-scene", print_scene, "print the effective scene as JSON and exit");
  cl.add_text("--path", path_file, "FILE",
              "render a film along a camera path (JSON: a start and walk/turn/hold segments, docs/films.md): one "
              "image per frame, -o a pattern with a frame number (out/frame-%06d.png); frames already written are "
              "skipped, so a stopped run goes on where it was");
  cl.add_number("--fps", fps, "F", "frames per second of --path, (0, 1000] (default 24)", sol::cli::in_range(1e-3, 1000.0));
  cl.add_text("--frames", frames, "A:B", "with --path: frames A to B-1 only (either may be left out; default all)");
  cl.add_text("--video", video, "FILE.mp4", "with --path: encode the frames with ffmpeg into FILE (.mp4, .mkv, .mov)");
  cl.add_flag("--progress", progress,
              "a progress line on stderr (percent, rays/s, time left; the default when stderr is a terminal)");
  cl.set_footer(
      "Camera options override the scene's. 8-bit formats get sRGB-encoded colours, float formats\n"
      "linear ones. On failure nothing is written and the exit status is non-zero (2 for bad usage).");
  cl.parse(argc, argv);
  const bool stereo = !stereo_mode.empty(), anaglyph = stereo_mode == "anaglyph";

  sol::Scene scene;
  try {
    scene = sol::cli::scene_argument(scene_arg);
    o.apply(scene);
    if (projection == "perspective") scene.camera.projection = sol::Projection::Perspective;
    if (projection == "equirectangular") scene.camera.projection = sol::Projection::Equirectangular;
    if (projection == "fisheye") scene.camera.projection = sol::Projection::Fisheye;
    if (fisheye_fov) scene.camera.fisheye_fov = *fisheye_fov;
    if (scene.camera.projection != sol::Projection::Perspective) scene.camera.frustum.reset();
    sol::validate(scene);
  } catch (const std::exception& e) {
    cl.fail(e.what());
  }
  if (spp == 0) spp = scene.samples;
  scene.samples = spp;  // what --print-scene shows
  if (print_scene) {
    std::printf("%s\n", sol::to_json(scene).c_str());
    return 0;
  }
  if (scene.camera.projection == sol::Projection::Equirectangular && width != 2 * height) {
    cl.fail("an equirectangular image needs --width = 2 x --height (360 x 180 degrees), got " + std::to_string(width) +
            " x " + std::to_string(height));
  }
  if (output.empty()) cl.fail("no output file: give -o OUT (see solrender --help)");
  if (!sol::programs::can_write(output)) cl.fail(output + ": no image format for this file name extension");
  if (!aov.empty() && std::filesystem::path(aov).extension() != ".exr") cl.fail("--aov needs an .exr file name, got " + aov);
  for (const std::string& path : {output, aov}) {
    if (!path.empty() && std::filesystem::is_directory(path)) cl.fail(path + ": cannot write: it is a directory");
  }
  if (!aov.empty()) {
    std::error_code ec_output, ec_aov;
    const auto a = std::filesystem::weakly_canonical(output, ec_output), b = std::filesystem::weakly_canonical(aov, ec_aov);
    if (!ec_output && !ec_aov && a == b) cl.fail("--aov " + aov + " is the same file as -o " + output + ": give two files");
  }
  if (flow.rk4() && device == "cpu") cl.fail("--integrator rk4 needs the Vulkan kernel (--device vulkan or auto)");

  const bool tty = isatty(fileno(stderr));
  const bool show_progress = tty || progress;
  const double eyes_count = stereo ? 2.0 : 1.0;

  // Films: --path, its frames and their files.
  std::optional<sol::CameraPath> camera_path;
  long first_frame = 0, end_frame = 0;
  if (!path_file.empty()) {
    try {
      camera_path = sol::load_camera_path(path_file);
    } catch (const std::exception& e) {
      cl.fail(e.what());
    }
    if (!aov.empty()) cl.fail("--aov is not available with --path (one image per frame)");
    if (!frame_number_end(output)) {
      cl.fail("-o " + output + ": with --path the name needs one frame number such as %06d (frame-%06d.png)");
    }
    const long count = camera_path->frame_count(fps);
    first_frame = 0;
    end_frame = count;
    if (!frames.empty()) {
      const auto colon = frames.find(':');
      if (colon == std::string::npos) cl.fail("--frames expects A:B (frames A to B-1; either may be left out), got '" + frames + "'");
      const std::string a = frames.substr(0, colon), b = frames.substr(colon + 1);
      if (!a.empty()) first_frame = cl.integer(a, "--frames (first)", 0, count);
      if (!b.empty()) end_frame = std::min(count, static_cast<long>(cl.integer(b, "--frames (end)", 0, 100000000)));
      if (first_frame >= end_frame) {
        cl.fail("--frames " + frames + ": no frames (the path has " + std::to_string(count) + " at " +
                std::to_string(fps) + " fps: 0.." + std::to_string(count - 1) + ")");
      }
    }
  } else if (!frames.empty() || !video.empty()) {
    cl.fail(!frames.empty() ? "--frames needs --path FILE" : "--video needs --path FILE");
  }
  std::string ffmpeg;
  if (!video.empty()) {
    ffmpeg = find_program("ffmpeg");
    if (ffmpeg.empty()) {
      cl.fail("--video needs ffmpeg, which is not installed (Debian: apt install ffmpeg); without --video the frames "
              "are written and 'ffmpeg -framerate F -i PATTERN -pix_fmt yuv420p out.mp4' encodes them");
    }
    if (std::filesystem::is_directory(video)) cl.fail("--video " + video + ": it is a directory");
  }

  // The progress line: finished fraction, rays per second so far, time left
  // at that rate; rewritten in place on a terminal, one line per 10% otherwise.
  const double total_rays = static_cast<double>(width) * eyes_count * height * spp;
  auto started = std::chrono::steady_clock::now();
  int last_tenth = -1;
  std::string progress_prefix;
  auto report = [&](double fraction) {
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    const double rate = seconds > 0 ? fraction * total_rays / seconds : 0.0;
    const double left = fraction > 0 ? seconds * (1.0 - fraction) / fraction : 0.0;
    if (!tty) {
      const int tenth = static_cast<int>(fraction * 10.0 + 1e-9);
      if (tenth == last_tenth) return;
      last_tenth = tenth;
    }
    std::fprintf(stderr, "%ssolrender: %s%3.0f%%  %.2f M rays/s  %.1f s left%s", tty ? "\r" : "", progress_prefix.c_str(),
                 100.0 * fraction, rate * 1e-6, left, tty ? "   " : "\n");
  };
  // A signal in any phase leaves no temporary behind (and no output).
  sol::programs::install_signal_cleanup();
  try {
    // The renderer, made once (a film's frames share it): the kernel, or the CPU.
    sol::programs::RendererChoice choice;
    choice.device = device == "vulkan" ? sol::programs::Device::Vulkan
                    : device == "cpu"  ? sol::programs::Device::Cpu
                                       : sol::programs::Device::Auto;
    choice.rk4 = flow.rk4();
    choice.rk4_step = flow.rk_step;
#ifndef NDEBUG
    choice.validation = true;  // validation layers in debug builds
#endif
    if (choice.device == sol::programs::Device::Vulkan && !sol::programs::has_vulkan()) {
      cl.fail("--device vulkan: this solrender was built without Vulkan (SOL_BUILD_VULKAN=OFF)");
    }
    const std::unique_ptr<sol::Renderer> renderer = sol::programs::make_renderer(
        choice, scene, [](const std::string& note) { std::fprintf(stderr, "solrender: %s\n", note.c_str()); });
    const bool cpu = dynamic_cast<const sol::CpuRenderer*>(renderer.get()) != nullptr;
    if (cpu && flow.rk4()) cl.fail("--integrator rk4 needs the Vulkan kernel");
    std::string where = renderer->description();
    if (cpu && threads) where = "cpu (" + std::to_string(threads) + " threads)";
    sol::RenderOptions render_options;
    render_options.width = width;
    render_options.height = height;
    render_options.samples = spp;
    render_options.threads = threads;
    render_options.max_dispatch_ms = 100.0;  // a device's dispatches in tiles of about 50 ms (a display's watchdog; progress)
    if (show_progress) render_options.progress = report;
    auto render_camera = [&](const sol::Camera& camera) {
      const sol::RenderResult both =
          stereo ? renderer->render_stereo(camera, ipd, render_options) : renderer->render(camera, render_options);
      return anaglyph ? to_anaglyph(both) : both;
    };

    if (camera_path) {
      // A film: frames first_frame..end_frame-1, each its own complete file;
      // frames already there (complete: files appear only whole) are skipped,
      // so a stopped run goes on where it was.
      long rendered = 0, skipped = 0;
      const auto film_started = std::chrono::steady_clock::now();
      const std::optional<sol::Lattice> lattice = scene.lattice();
      for (long k = first_frame; k < end_frame; ++k) {
        const std::string name = frame_name(output, k);
        if (std::filesystem::exists(name)) {
          ++skipped;
          continue;
        }
        const sol::Camera camera = camera_path->at(static_cast<double>(k) / fps, scene.camera, lattice);
        char prefix[96];
        std::snprintf(prefix, sizeof prefix, "frame %ld (%ld of %ld): ", k, k - first_frame + 1, end_frame - first_frame);
        progress_prefix = prefix;
        started = std::chrono::steady_clock::now();
        last_tenth = -1;
        const sol::RenderResult r = render_camera(camera);
        if (tty) std::fprintf(stderr, "\r");
        sol::programs::OutputFile image(name);
        const std::size_t non_finite = sol::programs::write_image(image, r.width, r.height, {"R", "G", "B", "A"}, r.rgba, true);
        image.commit();
        if (non_finite > 0) std::fprintf(stderr, "solrender: warning: %zu non-finite values in %s written as 0\n", non_finite, name.c_str());
        ++rendered;
      }
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - film_started).count();
      std::fprintf(stderr, "solrender: path %s: frames %ld..%ld at %g fps on %s: %ld rendered in %.2f s, %ld already there -> %s\n",
                   path_file.c_str(), first_frame, end_frame - 1, fps, where.c_str(), rendered, seconds, skipped,
                   output.c_str());
      if (!video.empty()) encode_video(ffmpeg, output, first_frame, fps, video);
      return 0;
    }

    const auto begin = std::chrono::steady_clock::now();
    sol::RenderResult r = render_camera(scene.camera);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    if (tty) std::fprintf(stderr, "\r");
    if (!cpu) {
      char buf[64];
      std::snprintf(buf, sizeof buf, " (kernel %.1f ms)", r.device_ms);
      where += buf;
    }
    // Both files complete before either replaces what was there: a failure
    // leaves the previous files as they were.
    sol::programs::OutputFile image(output);
    std::size_t non_finite = sol::programs::write_image(image, r.width, r.height, {"R", "G", "B", "A"}, r.rgba, true);
    std::optional<sol::programs::OutputFile> aovs;
    if (!aov.empty()) {
      aovs.emplace(aov);
      non_finite += sol::programs::write_image(*aovs, r.width, r.height, {"object", "distance", "Px", "Py", "Pz", "steps"},
                                               interleave_aovs(r), false);
    }
    image.commit();
    if (aovs) aovs->commit();
    if (non_finite > 0) {
      std::fprintf(stderr, "solrender: warning: %zu values were not finite and were written as 0 (a defect: please report "
                   "the scene and options)\n", non_finite);
    }
    const std::string samples = spp > 1 ? ", " + std::to_string(spp) + " samples per pixel" : "";
    std::fprintf(stderr, "solrender: %dx%d%s%s on %s: %.3f s, %.2f M rays/s -> %s\n", r.width, r.height,
                 anaglyph ? " (anaglyph)" : (stereo ? " (stereo)" : ""), samples.c_str(), where.c_str(), seconds,
                 r.width * static_cast<double>(r.height) * (anaglyph ? 2 : 1) * spp / seconds * 1e-6, output.c_str());
  } catch (const std::exception& e) {
    if (tty) std::fprintf(stderr, "\n");
    cl.fail(e.what());
  }
  return 0;
}
