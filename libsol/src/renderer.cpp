#include "sol/renderer.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "sol/denoise.hpp"
#include "sol/error.hpp"

namespace sol {

void Renderer::denoise(RenderResult& image, int eyes) { sol::denoise(image, eyes); }

RenderResult Renderer::render(const Camera& camera, const RenderOptions& options) {
  return render(std::span<const Camera>(&camera, 1), options);
}

RenderResult Renderer::render_stereo(const Camera& camera, double ipd, const RenderOptions& options) {
  const StereoEyes eyes = stereo_eyes(camera, ipd);
  const Camera both[] = {eyes.left, eyes.right};
  return render(both, options);
}

double available_memory_bytes() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  double kib = 0.0;
  std::string unit;
  while (in >> key >> kib) {
    std::getline(in, unit);
    if (key == "MemAvailable:") return kib * 1024.0;
  }
  return 0.0;
}

ProcessMemory process_memory() {
  std::ifstream in("/proc/self/status");
  ProcessMemory m;
  std::string line;
  while (std::getline(in, line)) {
    double kib = 0.0;
    if (std::sscanf(line.c_str(), "VmRSS: %lf kB", &kib) == 1) m.resident_bytes = kib * 1024.0;
    if (std::sscanf(line.c_str(), "VmHWM: %lf kB", &kib) == 1) m.peak_bytes = kib * 1024.0;
  }
  return m;
}

void validate_render(std::span<const Camera> eyes, const RenderOptions& options, const char* who, double bytes_per_pixel) {
  const std::string at = std::string(who) + ": ";
  for (const auto& [value, name] : {std::pair{options.width, "width"}, std::pair{options.height, "height"}}) {
    if (value < 1 || value > 16384) {
      throw InvalidArgument(at + name + " must be in [1, 16384], got " + std::to_string(value));
    }
  }
  if (options.samples < 1 || options.samples > 4096) {
    throw InvalidArgument(at + "samples must be in [1, 4096], got " + std::to_string(options.samples));
  }
  if (options.first_sample < 0 || options.first_sample > RenderOptions::kMaxFirstSample) {
    throw InvalidArgument(at + "first_sample must be in [0, 2^24], got " + std::to_string(options.first_sample));
  }
  if (options.first_sample > 0 && options.aovs) {
    throw InvalidArgument(at + "a batch of samples after the first (first_sample " + std::to_string(options.first_sample) +
                          ") renders no AOVs (they are sample 0's): set aovs to false");
  }
  if (!(options.max_dispatch_ms > 0.0)) throw InvalidArgument(at + "max_dispatch_ms must be > 0");
  if (eyes.empty()) throw InvalidArgument(at + "no eyes (one camera at least)");
  if (bytes_per_pixel > 0.0) {
    const double pixels = static_cast<double>(options.width) * options.height * static_cast<double>(eyes.size());
    const double need = pixels * bytes_per_pixel, available = available_memory_bytes();
    if (available > 0.0 && need > available) {
      char text[256];
      std::snprintf(text, sizeof text,
                    "%d x %d pixels x %zu eye(s) need about %.1f GiB of memory (%.0f bytes a pixel); %.1f GiB are "
                    "available: render a smaller image",
                    options.width, options.height, eyes.size(), need / 1073741824.0, bytes_per_pixel,
                    available / 1073741824.0);
      throw InvalidArgument(at + text);
    }
  }
  for (const Camera& camera : eyes) {
    validate(camera);
    if (camera.projection == Projection::Equirectangular && options.width != 2 * options.height) {
      throw InvalidArgument(at + "an equirectangular image needs width = 2 x height, got " + std::to_string(options.width) +
                            " x " + std::to_string(options.height));
    }
  }
}

RenderResult render_scene(Renderer& renderer, const Scene& scene, const RenderOptions& options) {
  renderer.set_world(scene);
  return renderer.render(scene.camera, options);
}

}  // namespace sol
