// render_bench: whole-image figures for the ray-marcher.
//
//  1. Throughput: rays per second and mean march steps per ray for every
//     preset at 512×512 (--size), on the Vulkan kernel (the device Sol::vk
//     picks: a GPU, else lavapipe; kernel time from timestamps, best of
//     --repeats runs, taken in rounds over the presets) and, but for the
//     exact presets (spheres: distance_bench
//     has its CPU cost), on the CPU reference renderer (wall time, all
//     threads). Written to render_throughput.csv.
//     The same presets with the kernel compiled with every feature against
//     the one specialised to the scene: render_features.csv.
//  2. Image error against run time: `plane` and `sandwich` rendered by the
//     kernel with the closed form and with RK4 at several steps, against a
//     CPU render in double (the reference), all with hit epsilon 2e-6: the
//     fraction of pixels whose hit mask differs, the worst arc-length and hit
//     point differences where both hit, and the kernel time. Written to
//     render_error_vs_time.csv.
//  3. Exact against bound: the `spheres` preset on the kernel with its balls
//     drawn by the distance bound or exactly (sol_shortest) and its
//     point light by the coordinate direction or exactly
//     (sol_connection.glsl, reach 0 and 2), at --size x 3/4 --size: kernel
//     time and time per ray against the all-bound variant. Written to
//     render_exact.csv.
//
//  4. Headset sizes: every preset on the kernel at --gpu-size² (default
//     2048², one eye of a current headset) and as a stereo frame of two such
//     eyes in one dispatch: frame time, M rays/s and the stereo frame's rate
//     (the goal on one H100-class GPU: 11 ms, 90 Hz), with the device's name.
//     Frames are recorded as a headset presenter records them
//     (MarchRenderer::record: colour alone, no AOVs, nothing read back),
//     kBackToBack in one submission, their mean time the figure (best of
//     the --repeats batches, at most 3). Before it, each preset's stereo
//     frames run back to back for kWarmUpSeconds: a GPU raises its clocks
//     only under sustained load (an H100 idles at 345 MHz and runs at 1980;
//     frames measured one at a time between read-backs ran up to 5x slow).
//     Written to render_gpu.csv. On a CPU device (lavapipe) it runs only
//     with --only gpu (it takes many minutes there; pass a smaller
//     --gpu-size).
//
//  6. Every lattice (--only lattices): one world, a ball of radius 0.3 at
//     the base point, in the golden lattice and in those of [[3, 1], [2, 1]]
//     (trace 4), [[5, 2], [2, 1]] (trace 6), [[9, 4], [2, 1]] (trace 10) and
//     [[-3, -1], [-2, -1]] (trace -4, its γ3 turning the fibre),
//     seen from the middle of each one's domain along z and along x + y,
//     on the kernel at --size², best of --repeats in rounds over the
//     lattices: time, M rays/s, mean steps, the images listed and the time
//     against the golden lattice's. Written to render_lattices.csv. Not in
//     the default run.
//
//  7. Light transport (--only path): the path tracer's error against
//     samples per pixel and against seconds, on the CPU renderer and on the
//     kernel: lattice-balls with its ball glowing and the sandwich with
//     its upper plane glowing, at 64×48, 1 to 256 samples per pixel
//     against the CPU's 2048-sample reference (other seeds): the relative
//     RMS error (over the pixels, of the three channels, over the
//     reference's RMS) and the wall time, raw and denoised (on the same
//     device: Renderer::denoise) with the filter's time, and the error
//     left if a filter found each pixel's light exactly (the reference's,
//     put back with the image's own albedo and emission: its guides' noise).
//     Written to path_convergence.csv (bench/plot_path_convergence.py
//     draws it). Not in the default run.
//
//  8. Path samples per second (--only path-rate): every preset (or
//     --scene) path traced on the kernel at --size², --spp paths a pixel
//     in one render after a warm-up render (the pipelines built): the
//     render's wall time (its dispatches and the read-back) and paths per
//     second, best of --repeats (at most 3). Written to path_rate.csv. Not
//     in the default run.
//
//  9. Objects (--only objects): a frame's time against the number of
//     objects: 10, 100, 1,000 and 10,000 small balls (radius 0.04) scattered
//     in the box [-2, 2]² x [-1, 1] over a floor (tests/support/crowd.hpp),
//     seen from outside the box and from inside it, at min(--size, 128)²,
//     on the kernel (where it takes the world) and the CPU renderer, best
//     of min(--repeats, 3) after a warm-up: wall time, M rays/s, mean steps
//     and the time against the 10 objects'. Written to render_objects.csv
//     (bench/plot_objects.py draws it). Not in the default run.
//
// 10. Enclosures (--only enclosure): the cost of one path inside an
//     enclosure against one path of lattice-balls, on the kernel (device
//     time, 32×24, 1 and 9 paths a pixel) and on the CPU renderer (wall
//     time, all threads, 16×12, 1 and more paths a pixel, as many as keep
//     the difference well above the noise): each scene's time at the two
//     counts, best of max(--repeats, 3), the difference over the paths it
//     adds is one path's cost. The enclosures are the furnaces of the
//     tests (the eye inside a glowing solid of albedo 0.6, emission 0.5):
//     an exact ball of radius 1 and a box. Written to enclosure_cost.csv.
//     Not in the default run.
//
//  5. Pipeline builds: every preset's first frame (16²) from a new
//     MarchRenderer, its pipelines built, with the specialisation constants
//     folded into the SPIR-V (the default on a CPU device) and handed to
//     the driver (the default on a GPU), after one build of each to warm
//     the driver's disk cache. Written to render_pipelines.csv.
//
// CSV fields holding a device name are quoted (names contain commas).
//
//   render_bench [--size N] [--error-size N] [--gpu-size N] [--repeats N] [--out-dir DIR]
//                [--only throughput|error|exact|gpu|pipelines|lattices|path|path-rate|objects|enclosure]
//                [--scene PRESET] [--kernel-only]
//
// For quick before/after figures of one change: --only throughput --scene
// lattice-balls --kernel-only (the specialised kernel alone, one preset).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <tuple>
#include <string>
#include <vector>

#include <sol/denoise.h>
#include <sol/sol.hpp>
#include <sol/vk/context.hpp>
#include <sol/vk/image.hpp>
#include <sol/vk/march.hpp>
#include <sol/vk/pipeline.hpp>

#include "image_file.hpp"
#include "command_line.hpp"
#include "output_file.hpp"
#include "support/crowd.hpp"
#include "support/paths.hpp"
#include "support/textures.hpp"

namespace {

double mean(const std::vector<float>& v) {
  double s = 0;
  for (float x : v) s += x;
  return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

struct ImageError {
  double mask_fraction = 0, distance = 0, point = 0;
};

ImageError compare(const sol::RenderResult& a, const sol::RenderResult& reference) {
  ImageError e;
  int differ = 0;
  for (std::size_t k = 0; k < a.object.size(); ++k) {
    if (a.object[k] != reference.object[k]) {
      ++differ;
    } else if (a.object[k] != 0) {
      e.distance = std::max(e.distance, static_cast<double>(std::abs(a.distance[k] - reference.distance[k])));
      const double dp = std::max({std::abs(a.px[k] - reference.px[k]), std::abs(a.py[k] - reference.py[k]),
                                  std::abs(a.pz[k] - reference.pz[k])});
      e.point = std::max(e.point, dp);
    }
  }
  e.mask_fraction = static_cast<double>(differ) / static_cast<double>(a.object.size());
  return e;
}

// What every section shares: the device, the options, the presets, and
// the files written at the end (name, contents).
struct Bench {
  sol::vk::Context& context;
  std::string quoted_device;
  int size, error_size, gpu_size, gpu_height, repeats, rate_spp;
  bool kernel_only;
  std::vector<std::string> presets;
  std::vector<std::pair<std::string, std::string>> files;
};

// 1. Throughput.
void section_throughput(Bench& b) {
  sol::vk::Context& context = b.context;
  const std::string& quoted_device = b.quoted_device;
  const int size = b.size;
  const int repeats = b.repeats;
  const bool kernel_only = b.kernel_only;
  const std::vector<std::string>& presets = b.presets;
  std::vector<std::pair<std::string, std::string>>& files = b.files;
  std::string throughput = "scene,device,width,height,ms,mrays_per_s,mean_steps\n";
  sol::vk::MarchRenderer general(context, {.all_features = true});
  std::string features = "scene,specialised_ms,general_ms,speedup\n";
  // The specialised kernels' times in rounds, each round one frame of
  // every preset: the shared machine's bursts of other work (seconds
  // long, longer than a preset's repeats) fall on all presets alike, so
  // that their ratios within one run hold. One renderer per preset
  // keeps its pipelines between rounds.
  const std::vector<std::string>& names = presets;
  std::vector<sol::Scene> scenes;
  for (const std::string& name : names) scenes.push_back(sol::preset_scene(name));
  std::vector<std::unique_ptr<sol::vk::MarchRenderer>> renderers;
  std::vector<double> bests(names.size(), 1e300);
  std::vector<sol::RenderResult> results(names.size());
  for (const sol::Scene& scene : scenes) {
    renderers.push_back(std::make_unique<sol::vk::MarchRenderer>(context));
    sol::render_scene(*renderers.back(), scene, {.width = size, .height = size});  // warm-up: shader compilation and caches
  }
  for (int k = 0; k < repeats; ++k) {
    for (std::size_t i = 0; i < names.size(); ++i) {
      results[i] = sol::render_scene(*renderers[i], scenes[i], {.width = size, .height = size});
      bests[i] = std::min(bests[i], results[i].device_ms);
    }
  }
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string& name = names[i];
    const sol::Scene& scene = scenes[i];
    const double best = bests[i];
    const sol::RenderResult& r = results[i];
    const double rays = static_cast<double>(size) * size;
    double best_general = 1e300;
    if (!kernel_only) sol::render_scene(general, scene, {.width = size, .height = size});  // warm-up
    for (int k = 0; k < (kernel_only ? 0 : repeats); ++k) {
      best_general = std::min(best_general, sol::render_scene(general, scene, {.width = size, .height = size}).device_ms);
    }
    char line[512];
    if (!kernel_only) {
      std::snprintf(line, sizeof line, "%s,%.2f,%.2f,%.2f\n", name.c_str(), best, best_general, best_general / best);
      features += line;
      std::fprintf(stderr, "features: %s", line);
    }
    std::snprintf(line, sizeof line, "%s,%s,%d,%d,%.2f,%.3f,%.2f\n", name.c_str(), quoted_device.c_str(), size, size,
                  best, rays / best * 1e-3, mean(r.steps));
    throughput += line;
    std::fprintf(stderr, "%s", line);
    if (kernel_only || sol::uses_exact(scene)) continue;  // its CPU cost: distance_bench (175 us per ray)
    sol::RenderOptions settings;
    settings.width = settings.height = size;
    const auto begin = std::chrono::steady_clock::now();
    const sol::RenderResult c = sol::render_cpu(scene, settings);
    const double cpu_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin).count();
    std::snprintf(line, sizeof line, "%s,\"cpu reference (double)\",%d,%d,%.2f,%.3f,%.2f\n", name.c_str(), size, size,
                  cpu_ms, rays / cpu_ms * 1e-3, mean(c.steps));
    throughput += line;
    std::fprintf(stderr, "%s", line);
  }
  files.emplace_back("render_throughput.csv", throughput);
  if (!kernel_only) files.emplace_back("render_features.csv", features);
}

// 6. Every lattice: the same world in several (asked for by name only).
void section_lattices(Bench& b) {
  sol::vk::Context& context = b.context;
  const std::string& quoted_device = b.quoted_device;
  const int size = b.size;
  const int repeats = b.repeats;
  std::vector<std::pair<std::string, std::string>>& files = b.files;
  struct Case {
    const char* name;
    sol::Monodromy monodromy;
  };
  const Case cases[] = {{"golden", {2, 1, 1, 1}},
                        {"trace4", {3, 1, 2, 1}},
                        {"trace6", {5, 2, 2, 1}},
                        {"trace10", {9, 4, 2, 1}},
                        {"trace-4", {-3, -1, -2, -1}}};
  struct Run {
    std::string label;
    sol::Scene scene;
    std::size_t images = 0;
    std::unique_ptr<sol::vk::MarchRenderer> renderer;
    double best = 1e300;
    sol::RenderResult result;
  };
  std::vector<Run> runs_of;
  for (const Case& c : cases) {
    for (const auto& [view, forward, up] : {std::tuple{"z", glm::dvec3(0, 0, -1), glm::dvec3(0, 1, 0)},
                                            std::tuple{"xy", glm::dvec3(1, 1, 0), glm::dvec3(0, 0, 1)}}) {
      Run r;
      r.label = std::string(c.name) + "," + view;
      sol::set_space(r.scene, sol::MonodromySpace{c.monodromy});
      const sol::Lattice lattice = *r.scene.lattice();
      r.scene.camera = {0.5 * (lattice.generators()[0] + lattice.generators()[1]) +
                            glm::dvec3(0.0, 0.0, 0.5 * lattice.height()),
                        forward, up, 90.0};
      r.scene.objects = {{sol::Ball{{0.0, 0.0, 0.0}, 0.3}, {0.9, 0.55, 0.3}}};
      r.scene.fog_density = 1.0 / 12.0;
      r.scene.max_distance = 12.0;
      r.scene.max_steps = 400;
      r.images = sol::quotient_images(r.scene).size();
      r.renderer = std::make_unique<sol::vk::MarchRenderer>(context);
      sol::render_scene(*r.renderer, r.scene, {.width = size, .height = size});  // warm-up
      runs_of.push_back(std::move(r));
    }
  }
  for (int k = 0; k < repeats; ++k) {
    for (Run& r : runs_of) {
      r.result = sol::render_scene(*r.renderer, r.scene, {.width = size, .height = size});
      r.best = std::min(r.best, r.result.device_ms);
    }
  }
  std::string csv = "lattice,view,device,width,height,images,ms,mrays_per_s,mean_steps,time_vs_golden\n";
  for (std::size_t i = 0; i < runs_of.size(); ++i) {
    const Run& r = runs_of[i];
    const Run& golden = runs_of[i % 2];  // the golden lattice's run of the same view
    char line[512];
    std::snprintf(line, sizeof line, "%s,%s,%d,%d,%zu,%.2f,%.3f,%.2f,%.3f\n", r.label.c_str(), quoted_device.c_str(), size,
                  size, r.images, r.best, static_cast<double>(size) * size / r.best * 1e-3, mean(r.result.steps),
                  r.best / golden.best);
    csv += line;
    std::fprintf(stderr, "%s", line);
  }
  files.emplace_back("render_lattices.csv", csv);
}

// 7. Light transport: the path tracer's error against samples and seconds,
// raw and denoised (asked for by name only).
void section_path(Bench& b) {
  sol::vk::Context& context = b.context;
  const std::string& quoted_device = b.quoted_device;
  std::vector<std::pair<std::string, std::string>>& files = b.files;
  sol::Scene lattice = sol::preset_scene("lattice-balls");
  lattice.objects[0].emission = {0.6, 0.35, 0.2};
  const sol::Scene sandwich = sol::test::glowing_sandwich();  // the gallery's glowing sandwich
  sol::vk::MarchRenderer kernel(context);
  sol::CpuRenderer cpu;
  std::string csv = "scene,device,width,height,spp,seconds,relative_rms_error,reference_spp,denoised_relative_rms_error,"
                    "denoise_seconds,exact_light_relative_rms_error\n";
  for (const auto& [name, scene] : {std::pair<std::string, const sol::Scene&>{"lattice-balls-glowing", lattice},
                                    std::pair<std::string, const sol::Scene&>{"sandwich-glowing", sandwich}}) {
    auto render = [&](sol::Renderer& renderer, int samples, std::uint64_t seed, double& seconds) {
      sol::RenderOptions settings;
      settings.width = 64;
      settings.height = 48;
      settings.samples = samples;
      settings.transport = sol::Transport::Path;
      settings.seed = seed;
      settings.guides = true;  // (the denoiser's albedo and normal)
      const auto start = std::chrono::steady_clock::now();
      sol::RenderResult r = sol::render_scene(renderer, scene, settings);
      seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      return r;
    };
    // One reference for both: the CPU's, in double.
    double reference_seconds = 0.0;
    const sol::RenderResult reference = render(cpu, 2048, 1000, reference_seconds);
    double reference_squares = 0.0;
    for (std::size_t k = 0; k < reference.rgba.size(); ++k) {
      if (k % 4 != 3) reference_squares += static_cast<double>(reference.rgba[k]) * reference.rgba[k];
    }
    const auto error_of = [&](const std::vector<float>& rgba) {
      double squares = 0.0;
      for (std::size_t k = 0; k < rgba.size(); ++k) {
        if (k % 4 != 3) squares += std::pow(static_cast<double>(rgba[k]) - reference.rgba[k], 2.0);
      }
      return std::sqrt(squares / reference_squares);
    };
    const auto error = [&](const sol::RenderResult& r) { return error_of(r.rgba); };
    // The error left if a filter found every pixel's light exactly: the
    // reference's light ((colour - emission) / albedo, where its albedo is
    // at least the filter's floor; elsewhere its colour) put back with the
    // image's own albedo and emission, the means of its N samples, as the
    // filter puts them back. What that leaves is the guides' own noise
    // (which of the pixel's objects, pattern and glow its samples met).
    const auto exact_light_error = [&](const sol::RenderResult& r) {
      std::vector<float> rgba = r.rgba;
      for (std::size_t p = 0; p < rgba.size() / 4; ++p) {
        for (std::size_t c = 0; c < 3; ++c) {
          const double albedo = reference.albedo[3 * p + c];
          rgba[4 * p + c] =
              albedo >= sol::kernel::kDenoiseMinAlbedo
                  ? static_cast<float>(r.emission[3 * p + c] + r.albedo[3 * p + c] *
                                                                   (reference.rgba[4 * p + c] - reference.emission[3 * p + c]) /
                                                                   albedo)
                  : reference.rgba[4 * p + c];
        }
      }
      return error_of(rgba);
    };
    double warm = 0.0;
    sol::RenderResult warm_image = render(kernel, 1, 0, warm);  // the kernel's pipelines built first
    kernel.denoise(warm_image);                                  // (and its filter's)
    for (sol::Renderer* renderer : {static_cast<sol::Renderer*>(&cpu), static_cast<sol::Renderer*>(&kernel)}) {
      const std::string where = renderer == &cpu ? "cpu" : quoted_device;
      for (int spp = 1; spp <= 256; spp *= 2) {
        double seconds = 0.0;
        sol::RenderResult r = render(*renderer, spp, static_cast<std::uint64_t>(spp), seconds);
        const double raw = error(r);
        const double exact_light = exact_light_error(r);
        const auto start = std::chrono::steady_clock::now();
        renderer->denoise(r);
        const double denoise_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        char line[512];
        std::snprintf(line, sizeof line, "%s,%s,64,48,%d,%.3f,%.5f,2048,%.5f,%.4f,%.5f\n", name.c_str(), where.c_str(),
                      spp, seconds, raw, error(r), denoise_seconds, exact_light);
        csv += line;
        std::fprintf(stderr, "%s", line);
      }
    }
  }
  files.emplace_back("path_convergence.csv", csv);
}

// 8. Path samples per second, per preset (asked for by name only).
void section_path_rate(Bench& b) {
  sol::vk::Context& context = b.context;
  const std::string& quoted_device = b.quoted_device;
  const int size = b.size;
  const int repeats = b.repeats;
  const int rate_spp = b.rate_spp;
  const std::vector<std::string>& presets = b.presets;
  std::vector<std::pair<std::string, std::string>>& files = b.files;
  std::string csv = "scene,device,width,height,spp,seconds,mpaths_per_s\n";
  for (const std::string& name : presets) {
    const sol::Scene scene = sol::preset_scene(name);
    sol::vk::MarchRenderer kernel(context);
    sol::RenderOptions settings;
    settings.width = settings.height = size;
    settings.transport = sol::Transport::Path;
    settings.samples = 1;
    sol::render_scene(kernel, scene, settings);  // warm-up: the path pipelines built
    settings.samples = rate_spp;
    double best = 1e300;
    for (int k = 0; k < std::min(repeats, 3); ++k) {
      settings.seed = static_cast<std::uint64_t>(k);
      const auto start = std::chrono::steady_clock::now();
      sol::render_scene(kernel, scene, settings);
      best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    char line[512];
    std::snprintf(line, sizeof line, "%s,%s,%d,%d,%d,%.3f,%.3f\n", name.c_str(), quoted_device.c_str(), size, size, rate_spp,
                  best, static_cast<double>(size) * size * rate_spp / best * 1e-6);
    csv += line;
    std::fprintf(stderr, "%s", line);
  }
  files.emplace_back("path_rate.csv", csv);
}

// 2. Image error against run time.
void section_error(Bench& b) {
  sol::vk::Context& context = b.context;
  const int error_size = b.error_size;
  const int repeats = b.repeats;
  std::vector<std::pair<std::string, std::string>>& files = b.files;
  std::string errors = "scene,integrator,setting,mask_mismatch_fraction,max_distance_error,max_point_error,ms\n";
  for (const char* name : {"plane", "sandwich"}) {
    sol::Scene scene = sol::preset_scene(name);
    // A hit epsilon near float resolution, so that the march's own stopping
    // tolerance does not hide the flow's error.
    scene.hit_epsilon = 2e-6;
    sol::RenderOptions settings;
    settings.width = settings.height = error_size;
    const sol::RenderResult reference = sol::render_cpu(scene, settings);
    struct Variant {
      const char* integrator;
      double step;
    };
    for (const Variant v : {Variant{"closed", 0.0}, Variant{"rk4", 0.1}, Variant{"rk4", 0.03}, Variant{"rk4", 0.01},
                            Variant{"rk4", 0.003}}) {
      sol::vk::MarchOptions options;
      if (std::strcmp(v.integrator, "rk4") == 0) {
        options.integrator = sol::vk::Integrator::RK4;
        options.rk4_step = v.step;
      }
      sol::vk::MarchRenderer r(context, options);
      sol::render_scene(r, scene, {.width = error_size, .height = error_size});  // warm-up
      double best = 1e300;
      sol::RenderResult image;
      for (int k = 0; k < std::min(repeats, 3); ++k) {
        image = sol::render_scene(r, scene, {.width = error_size, .height = error_size});
        best = std::min(best, image.device_ms);
      }
      const ImageError e = compare(image, reference);
      char line[512];
      char setting[64];
      std::snprintf(setting, sizeof setting, v.step > 0 ? "h=%g" : "-", v.step);
      std::snprintf(line, sizeof line, "%s,%s,%s,%.5f,%.3e,%.3e,%.2f\n", name, v.integrator, setting,
                    e.mask_fraction, e.distance, e.point, best);
      errors += line;
      std::fprintf(stderr, "%s", line);
    }
  }
  files.emplace_back("render_error_vs_time.csv", errors);
}

// 3. Exact spheres and lights against the bound-based ones.
void section_exact(Bench& b) {
  sol::vk::Context& context = b.context;
  const int size = b.size;
  const int repeats = b.repeats;
  std::vector<std::pair<std::string, std::string>>& files = b.files;
  std::string exact = "balls,light,falloff,shadows,width,height,ms,us_per_ray,ratio_to_bound\n";
  const int w = size, h = std::max(1, size * 3 / 4);
  sol::vk::MarchRenderer renderer(context);
  double bound_ms = 0;
  struct Variant {
    bool exact_balls, exact_light;
    double reach;
    sol::Falloff falloff;
    bool shadows;
  };
  using F = sol::Falloff;
  for (const Variant v : {Variant{false, false, 0.0, F::Auto, false}, Variant{true, false, 0.0, F::Auto, false},
                          Variant{false, true, 0.0, F::InverseSquare, false}, Variant{false, true, 0.0, F::Geodesic, false},
                          Variant{false, true, 0.0, F::Geodesic, true}, Variant{true, true, 0.0, F::Geodesic, false},
                          Variant{true, true, 0.0, F::Geodesic, true}, Variant{false, true, 2.0, F::Geodesic, false},
                          Variant{false, true, 2.0, F::Geodesic, true}}) {
    sol::Scene scene = sol::preset_scene("spheres");
    for (sol::SceneObject& o : scene.objects) std::get<sol::Ball>(o.shape).exact = v.exact_balls;
    for (sol::Light& l : scene.lights) {
      l.exact = v.exact_light;
      l.reach = v.reach;
      l.falloff = v.falloff;
      l.shadows = v.shadows;
    }
    sol::render_scene(renderer, scene, {.width = w, .height = h});  // warm-up: tables, shader compilation
    double best = 1e300;
    for (int k = 0; k < repeats; ++k) best = std::min(best, sol::render_scene(renderer, scene, {.width = w, .height = h}).device_ms);
    if (!v.exact_balls && !v.exact_light) bound_ms = best;
    char light[32];
    std::snprintf(light, sizeof light, v.exact_light ? "exact reach %g" : "coordinate", v.reach);
    const char* falloff = sol::falloff_of(scene.lights[0]) == F::Geodesic ? "geodesic" : "inverse-square";
    char line[256];
    std::snprintf(line, sizeof line, "%s,%s,%s,%s,%d,%d,%.2f,%.3f,%.2f\n", v.exact_balls ? "exact" : "bound", light,
                  falloff, v.shadows ? "yes" : "no", w, h, best, best * 1e3 / (static_cast<double>(w) * h),
                  best / bound_ms);
    exact += line;
    std::fprintf(stderr, "exact: %s", line);
  }
  files.emplace_back("render_exact.csv", exact);
}

// 5. Pipeline builds: a new renderer's first frame (16², the world's
// pipelines built) with the specialisation constants folded into the
// SPIR-V and handed to the driver. Each variant is built once first, so
// that the driver's own disk cache (Mesa's) is warm for both, as for a
// program run before.
void section_pipelines(Bench& b) {
  sol::vk::Context& context = b.context;
  const std::string& quoted_device = b.quoted_device;
  const std::vector<std::string>& presets = b.presets;
  std::vector<std::pair<std::string, std::string>>& files = b.files;
  std::string builds = "scene,device,folded_s,driver_s,ratio\n";
  for (const std::string& name : presets) {
    const sol::Scene scene = sol::preset_scene(name);
    double seconds[2] = {0.0, 0.0};
    for (const bool fold : {true, false}) {
      const sol::vk::SpecializationFolding folding =
          fold ? sol::vk::SpecializationFolding::Folded : sol::vk::SpecializationFolding::Driver;
      {
        sol::vk::MarchRenderer warm(context, {.specialization_folding = folding});
        sol::render_scene(warm, scene, {.width = 16, .height = 16});  // warms the driver's cache
      }
      sol::vk::MarchRenderer renderer(context, {.specialization_folding = folding});
      const auto start = std::chrono::steady_clock::now();
      sol::render_scene(renderer, scene, {.width = 16, .height = 16});
      seconds[fold ? 0 : 1] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    char line[256];
    std::snprintf(line, sizeof line, "%s,%s,%.2f,%.2f,%.1f\n", name.c_str(), quoted_device.c_str(), seconds[0],
                  seconds[1], seconds[1] / seconds[0]);
    builds += line;
    std::fprintf(stderr, "pipelines: %s", line);
  }
  files.emplace_back("render_pipelines.csv", builds);
}

// 4. Headset sizes: one eye at gpu_size × gpu_height (square by default), and a stereo frame of two in one dispatch.
void section_headset(Bench& b) {
  sol::vk::Context& context = b.context;
  const std::string& quoted_device = b.quoted_device;
  const int gpu_size = b.gpu_size;
  const int gpu_height = b.gpu_height;
  const int repeats = b.repeats;
  const std::vector<std::string>& presets = b.presets;
  std::vector<std::pair<std::string, std::string>>& files = b.files;
  std::string gpu = "scene,device,width,height,mono_ms,mrays_per_s,stereo_ms,stereo_hz\n";
  sol::vk::MarchRenderer renderer(context);
  const int batches = std::min(repeats, 3);
  constexpr int kBackToBack = 8;
  constexpr double kWarmUpSeconds = 1.5;
  sol::vk::StorageImage target(context, 2 * static_cast<std::uint32_t>(gpu_size),
                               static_cast<std::uint32_t>(gpu_height));
  // Each frame's writes (the target, the deferred passes' lists) complete
  // before the next frame's commands touch them.
  const auto between_frames = [](VkCommandBuffer cb) {
    sol::vk::record_memory_barrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                                   VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT,
                                   VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                                   VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT);
  };
  // The mean time of one frame of `eyes` over a batch recorded back to back.
  const auto batch_ms = [&](std::span<const sol::Camera> eyes) {
    return sol::vk::run_recorded(context, [&](VkCommandBuffer cb) {
             for (int f = 0; f < kBackToBack; ++f) {
               if (f > 0) between_frames(cb);
               renderer.record(cb, eyes, gpu_size, gpu_height, target);
             }
           }) /
           kBackToBack;
  };
  for (const std::string& name : presets) {
    const sol::Scene scene = sol::preset_scene(name);
    renderer.set_world(scene);
    const sol::StereoEyes stereo_eyes = sol::stereo_eyes(scene.camera, 0.064);
    const sol::Camera both[] = {stereo_eyes.left, stereo_eyes.right};
    const std::span<const sol::Camera> one(&scene.camera, 1);
    const auto start = std::chrono::steady_clock::now();
    do {
      batch_ms(both);  // warm-up: compilation, caches and the device's clocks
    } while (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < kWarmUpSeconds);
    double mono = 1e300, stereo = 1e300;
    for (int k = 0; k < batches; ++k) {
      mono = std::min(mono, batch_ms(one));
      stereo = std::min(stereo, batch_ms(both));
    }
    char line[512];
    std::snprintf(line, sizeof line, "%s,%s,%d,%d,%.2f,%.3f,%.2f,%.1f\n", name.c_str(), quoted_device.c_str(),
                  gpu_size, gpu_height, mono, static_cast<double>(gpu_size) * gpu_height / mono * 1e-3, stereo,
                  1e3 / stereo);
    gpu += line;
    std::fprintf(stderr, "gpu: %s", line);
  }
  files.emplace_back("render_gpu.csv", gpu);
}

// 9. Objects: a frame's time against the number of objects (see the top).
void section_objects(Bench& b) {
  sol::vk::Context& context = b.context;
  const int size = std::min(b.size, 128), repeats = b.repeats;
  std::string csv = "objects,camera,device,width,height,ms,mrays_per_s,mean_steps,time_vs_10\n";
  const double rays = static_cast<double>(size) * size;
  for (const char* device : {"kernel", "cpu"}) {
    double first[2] = {0.0, 0.0};
    for (const std::size_t count : {10, 100, 1000, 10000}) {
      sol::Scene scene;
      scene.objects = sol::test::scattered_balls(count);  // (and the default light)
      for (int c = 0; c < 2; ++c) {
        scene.camera = c == 0 ? sol::test::crowd_camera_outside() : sol::test::crowd_camera_inside();
        const char* camera = c == 0 ? "outside" : "inside";
        std::unique_ptr<sol::Renderer> renderer;
        if (std::strcmp(device, "cpu") == 0) {
          renderer = std::make_unique<sol::CpuRenderer>();
        } else if (const std::string why = sol::vk::MarchRenderer::unsupported(scene); why.empty()) {
          renderer = std::make_unique<sol::vk::MarchRenderer>(context);
        } else {
          std::fprintf(stderr, "objects: %zu, %s: not on the kernel (%s)\n", count, camera, why.c_str());
          csv += std::to_string(count) + "," + camera + ",kernel,,,,,,\n";
          continue;
        }
        const sol::RenderOptions options{.width = size, .height = size};
        sol::render_scene(*renderer, scene, options);  // warm-up: the world prepared, pipelines built
        double best = 1e300;
        sol::RenderResult r;
        for (int k = 0; k < std::min(repeats, 3); ++k) {
          const auto begin = std::chrono::steady_clock::now();
          r = sol::render_scene(*renderer, scene, options);
          best = std::min(best, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin).count());
        }
        if (count == 10) first[c] = best;
        char line[512];
        std::snprintf(line, sizeof line, "%zu,%s,\"%s\",%d,%d,%.2f,%.4f,%.2f,%.2f\n", count, camera,
                      renderer->description().c_str(), size, size, best, rays / best * 1e-3, mean(r.steps), best / first[c]);
        csv += line;
        std::fprintf(stderr, "%s", line);
      }
    }
  }
  b.files.emplace_back("render_objects.csv", csv);
}

// 10. The cost of a path in an enclosure (asked for by name only).
void section_enclosure(Bench& b) {
  struct Case {
    const char* name;
    sol::Scene scene;
    int cpu_samples;  // the CPU's higher count (its cheap paths need many to be measured)
  };
  const std::vector<Case> cases = {
      {"lattice-balls", sol::preset_scene("lattice-balls"), 65},
      {"furnace-exact-ball", sol::test::furnace(0.0), 5},
      {"furnace-box", sol::test::furnace_in(sol::Box{{0.1, -0.1, 0.05}, {0.6, 0.5, 0.4}}), 17},
  };
  std::string csv = "scene,device,width,height,spp_low,spp_high,seconds_low,seconds_high,us_per_path,vs_lattice_balls\n";
  for (const char* device : {"kernel", "cpu"}) {
    const bool on_cpu = std::strcmp(device, "cpu") == 0;
    std::unique_ptr<sol::Renderer> renderer;
    if (on_cpu) {
      renderer = std::make_unique<sol::CpuRenderer>();
    } else {
      renderer = std::make_unique<sol::vk::MarchRenderer>(b.context);
    }
    const int width = on_cpu ? 16 : 32, height = on_cpu ? 12 : 24;
    double lattice_cost = 0.0;
    for (const Case& c : cases) {
      const int counts[2] = {1, on_cpu ? c.cpu_samples : 9};
      double seconds[2] = {1e300, 1e300};
      for (int round = 0; round < std::max(b.repeats, 3) + 1; ++round) {
        for (int i = 0; i < 2; ++i) {
          sol::RenderOptions options{.width = width, .height = height};
          options.transport = sol::Transport::Path;
          options.samples = counts[i];
          options.seed = static_cast<std::uint64_t>(round);
          const auto begin = std::chrono::steady_clock::now();
          const sol::RenderResult r = sol::render_scene(*renderer, c.scene, options);
          const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
          if (round > 0) seconds[i] = std::min(seconds[i], on_cpu ? wall : r.device_ms * 1e-3);  // round 0: warm-up
        }
      }
      const double paths = static_cast<double>(width) * height * (counts[1] - counts[0]);
      const double cost = std::max(seconds[1] - seconds[0], 0.0) / paths * 1e6;
      if (std::strcmp(c.name, "lattice-balls") == 0) lattice_cost = cost;
      char line[512];
      std::snprintf(line, sizeof line, "%s,\"%s\",%d,%d,%d,%d,%.4f,%.4f,%.2f,%.1f\n", c.name,
                    renderer->description().c_str(), width, height, counts[0], counts[1], seconds[0], seconds[1], cost,
                    lattice_cost > 0.0 ? cost / lattice_cost : 0.0);
      csv += line;
      std::fprintf(stderr, "%s", line);
    }
  }
  b.files.emplace_back("enclosure_cost.csv", csv);
}

}  // namespace

int main(int argc, char** argv) {
  sol::programs::install_texture_reader();  // scene files' "texture" keys
  int size = 512, error_size = 128, gpu_size = 2048, gpu_height = 0, repeats = 5, rate_spp = 16;
  std::string out_dir = ".", only, scene_name;
  bool kernel_only = false;
  sol::cli::CommandLine cl("render_bench", "[options]",
                          "Measures rays per second, image error against run time and the exact objects' cost.");
  cl.add_integer("--size", size, 1, 8192, "N", "image side for throughput and the exact section (default 512)");
  cl.add_integer("--error-size", error_size, 1, 4096, "N", "image side for error against run time (default 128)");
  cl.add_integer("--gpu-size", gpu_size, 1, 8192, "N", "one eye's side for the headset section (default 2048)");
  cl.add_integer("--gpu-height", gpu_height, 1, 8192, "H",
                 "one eye's height for the headset section, its width --gpu-size (default: square)");
  cl.add_integer("--repeats", repeats, 1, 1000, "N", "dispatches per figure, the best counts (default 5)");
  cl.add_integer("--spp", rate_spp, 1, 65536, "N", "paths a pixel for the path-rate section (default 16)");
  cl.add_text("--out-dir", out_dir, "DIR", "where the CSVs go (default .)");
  cl.add_choice("--only", only, {"throughput", "error", "exact", "gpu", "pipelines", "lattices", "path", "path-rate", "objects",
                               "enclosure"},
                "run one section and write its files (lattices, path, path-rate: only so)");
  cl.add_choice("--scene", scene_name, sol::preset_names(),
                "throughput, headset, pipeline and path-rate sections: this preset only");
  cl.add_flag("--kernel-only", kernel_only,
              "throughput section: the specialised kernel alone (no all-features kernel, no CPU reference)");
  cl.set_footer("Writes render_throughput.csv, render_features.csv, render_error_vs_time.csv,\n"
                "render_exact.csv, render_gpu.csv (on a CPU device only with --only gpu),\n"
                "render_pipelines.csv, (--only lattices) render_lattices.csv, (--only objects)\n"
                "render_objects.csv, (--only enclosure) enclosure_cost.csv, (--only path)\n"
                "path_convergence.csv and (--only path-rate) path_rate.csv to DIR.");
  cl.parse(argc, argv);
  // Refused now, not after minutes of measuring.
  if (!std::filesystem::is_directory(out_dir)) cl.fail("--out-dir " + out_dir + ": not a directory");
  // The presets the throughput, headset and pipeline sections take (--scene: one).
  std::vector<std::string> presets;
  for (const std::string& name : sol::preset_names()) {
    if (scene_name.empty() || name == scene_name) presets.push_back(name);
  }
  try {
    sol::vk::Context context;
    const std::string device = context.device_name();
    const std::string quoted_device = "\"vulkan " + device + "\"";
    std::fprintf(stderr, "render_bench: Vulkan device '%s'\n", device.c_str());

    auto runs = [&](const char* section) { return only.empty() || only == section; };
    if (gpu_height == 0) gpu_height = gpu_size;
    Bench b{context, quoted_device, size, error_size, gpu_size, gpu_height, repeats, rate_spp, kernel_only, presets, {}};
    // The sections in the order they run; lattices, path, path-rate and
    // objects only when asked for by name.
    if (runs("throughput")) section_throughput(b);
    if (only == "lattices") section_lattices(b);
    if (only == "path") section_path(b);
    if (only == "path-rate") section_path_rate(b);
    if (only == "objects") section_objects(b);
    if (only == "enclosure") section_enclosure(b);
    if (runs("error")) section_error(b);
    if (runs("exact")) section_exact(b);
    // Headset sizes: on a CPU device only when asked for (many minutes there).
    if (only.empty() && context.is_cpu()) {
      std::fprintf(stderr, "render_bench: '%s' is a CPU device: section 4 (headset sizes) only with --only gpu\n",
                   device.c_str());
    }
    if (only == "gpu" || (only.empty() && !context.is_cpu())) section_headset(b);
    if (runs("pipelines")) section_pipelines(b);

    for (const auto& [name, text] : b.files) {
      sol::programs::write_text_file(out_dir + "/" + name, text);  // complete or absent
      std::fprintf(stderr, "render_bench: wrote %s/%s\n", out_dir.c_str(), name.c_str());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "render_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
