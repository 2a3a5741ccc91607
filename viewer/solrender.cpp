// solrender: renders a Sol scene headless to an image file (any format
// OpenImageIO writes) and optionally its AOVs to an EXR.
//
//   solrender --scene plane -o plane.png
//   solrender --scene my.json -o out.exr --aov aov.exr --width 256 --height 256
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <optional>
#include <string>
#include <thread>
#include <unistd.h>
#include <vector>

#include <sol/sol.hpp>
#ifdef SOL_HAVE_VULKAN
#include <sol/vk/context.hpp>
#include <sol/vk/march.hpp>
#endif

#include "command_line.hpp"
#include "image_file.hpp"

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

}  // namespace

int main(int argc, char** argv) {
  std::string scene_arg = "plane", output, aov, device = "auto", integrator = "closed";
  double rk_step = 0.01, ipd = 0.064;
  bool stereo = false, print_scene = false, progress = false;
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
  cl.add_integer("--spp", spp, 1, 4096, "N",
                 "samples per pixel, 1..4096 (default: the scene's \"samples\", 1 unless it says): anti-aliasing, "
                 "the colour the mean of N rays through the pixel (an evenly spread sequence; sample 1 is the "
                 "centre); the AOVs stay the centre's");
  cl.add_choice("--device", device, {"auto", "vulkan", "cpu"},
                "where to render: auto takes Vulkan (a GPU, else lavapipe) when available and the CPU renderer "
                "otherwise (default auto)");
  cl.add_choice("--integrator", integrator, {"closed", "rk4"}, "the kernel's geodesic flow (default closed; vulkan only)");
  cl.add_number("--rk-step", rk_step, "H", "RK4 substep in arc length for --integrator rk4 (default 0.01)",
                sol::cli::positive());
  cl.add_flag("--stereo", stereo, "both eyes side by side (image width 2 W)");
  cl.add_number("--ipd", ipd, "D", "eye separation in Sol units for --stereo, [0, 10] (default 0.064)",
                sol::cli::in_range(0.0, 10.0));
  cl.add_integer("--threads", threads, 1, 1024, "N", "CPU threads for --device cpu (default: all)");
  cl.add_flag("--print-scene", print_scene, "print the effective scene as JSON and exit");
  cl.add_flag("--progress", progress,
              "a progress line on stderr (percent, rays/s, time left; the default when stderr is a terminal)");
  cl.set_footer(
      "Camera options override the scene's. 8-bit formats get sRGB-encoded colours, float formats\n"
      "linear ones. On failure nothing is written and the exit status is non-zero (2 for bad usage).");
  cl.parse(argc, argv);

  sol::Scene scene;
  try {
    scene = sol::cli::scene_argument(scene_arg);
    o.apply(scene);
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
  if (integrator == "rk4" && device == "cpu") cl.fail("--integrator rk4 needs the Vulkan kernel (--device vulkan or auto)");

  const bool tty = isatty(fileno(stderr));
  const bool show_progress = tty || progress;
  // The progress line: finished fraction, rays per second so far, time left
  // at that rate; rewritten in place on a terminal, one line per 10% otherwise.
  const double total_rays = static_cast<double>(width) * (stereo ? 2 : 1) * height * spp;
  const auto started = std::chrono::steady_clock::now();
  int last_tenth = -1;
  auto report = [&](double fraction) {
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    const double rate = seconds > 0 ? fraction * total_rays / seconds : 0.0;
    const double left = fraction > 0 ? seconds * (1.0 - fraction) / fraction : 0.0;
    if (!tty) {
      const int tenth = static_cast<int>(fraction * 10.0 + 1e-9);
      if (tenth == last_tenth) return;
      last_tenth = tenth;
    }
    std::fprintf(stderr, "%ssolrender: %3.0f%%  %.2f M rays/s  %.1f s left%s", tty ? "\r" : "", 100.0 * fraction,
                 rate * 1e-6, left, tty ? "   " : "\n");
  };
  // A signal in any phase leaves no temporary behind (and no output).
  sol::programs::install_signal_cleanup();
  try {
    sol::RenderResult r;
    std::string where;
    double seconds = 0;
    bool rendered = false;
#ifdef SOL_HAVE_VULKAN
    if (device == "auto" && !sol::vk::MarchRenderer::supports(scene)) {
      std::fprintf(stderr, "solrender: exact point lights with a reach above %g are CPU-only; rendering on the CPU\n",
                   sol::ConnectionTable::kReach);
    } else if (device != "cpu") {
      std::optional<sol::vk::Context> context;
      try {
        sol::vk::ContextOptions context_options;
        context_options.pipeline_cache_dir = sol::vk::default_pipeline_cache_dir();  // compiled kernels kept between runs
#ifndef NDEBUG
        context_options.validation = true;  // validation layers in debug builds
#endif
        context.emplace(context_options);
      } catch (const std::exception& e) {
        if (device == "vulkan") throw;
        std::fprintf(stderr, "solrender: no Vulkan device (%s); rendering on the CPU\n", e.what());
      }
      if (context) {
        sol::vk::MarchOptions options;
        options.integrator = integrator == "rk4" ? sol::vk::Integrator::RK4 : sol::vk::Integrator::ClosedForm;
        options.rk4_step = rk_step;
        sol::vk::MarchRenderer renderer(*context, options);
        const auto begin = std::chrono::steady_clock::now();
        double device_ms = 0;
        renderer.set_world(scene);
        std::vector<sol::Camera> eyes{scene.camera};
        if (stereo) {
          const sol::StereoEyes pair = sol::stereo_eyes(scene.camera, ipd);
          eyes = {pair.left, pair.right};
        }
        // In tiles of at most about 100 ms on the device (a display's watchdog; progress).
        sol::vk::RenderOptions render_options;
        render_options.samples = spp;
        if (show_progress) render_options.progress = report;
        r = renderer.render(eyes, width, height, render_options, &device_ms);
        if (tty) std::fprintf(stderr, "\r");
        seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
        char buf[256];
        std::snprintf(buf, sizeof buf, "vulkan '%s' (kernel %.1f ms)", context->device_name().c_str(), device_ms);
        where = buf;
        rendered = true;
      }
    }
#else
    if (device == "vulkan") cl.fail("--device vulkan: this solrender was built without Vulkan (SOL_BUILD_VULKAN=OFF)");
#endif
    if (!rendered) {
      if (integrator == "rk4") cl.fail("--integrator rk4 needs the Vulkan kernel");
      sol::RenderSettings settings;
      settings.width = width;
      settings.height = height;
      settings.threads = threads;
      settings.samples = spp;
      if (show_progress) settings.progress = report;
      const unsigned used_threads = threads ? threads : std::max(1u, std::thread::hardware_concurrency());
      const auto begin = std::chrono::steady_clock::now();
      r = stereo ? sol::render_cpu_stereo(scene, settings, ipd) : sol::render_cpu(scene, settings);
      seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
      if (tty) std::fprintf(stderr, "\r");
      where = "cpu (" + std::to_string(used_threads) + " threads)";
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
                 stereo ? " (stereo)" : "", samples.c_str(), where.c_str(), seconds,
                 r.width * static_cast<double>(r.height) * spp / seconds * 1e-6, output.c_str());
  } catch (const std::exception& e) {
    if (tty) std::fprintf(stderr, "\n");
    cl.fail(e.what());
  }
  return 0;
}
