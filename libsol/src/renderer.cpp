#include "sol/renderer.hpp"

#include <cmath>
#include <string>

#include "sol/error.hpp"

namespace sol {

RenderResult Renderer::render(const Camera& camera, const RenderOptions& options) {
  return render(std::span<const Camera>(&camera, 1), options);
}

RenderResult Renderer::render_stereo(const Camera& camera, double ipd, const RenderOptions& options) {
  const StereoEyes eyes = stereo_eyes(camera, ipd);
  const Camera both[] = {eyes.left, eyes.right};
  return render(both, options);
}

void validate_render(std::span<const Camera> eyes, const RenderOptions& options, const char* who) {
  const std::string at = std::string(who) + ": ";
  for (const auto& [value, name] : {std::pair{options.width, "width"}, std::pair{options.height, "height"}}) {
    if (value < 1 || value > 16384) {
      throw InvalidArgument(at + name + " must be in [1, 16384], got " + std::to_string(value));
    }
  }
  if (options.samples < 1 || options.samples > 4096) {
    throw InvalidArgument(at + "samples must be in [1, 4096], got " + std::to_string(options.samples));
  }
  if (!(options.max_dispatch_ms > 0.0)) throw InvalidArgument(at + "max_dispatch_ms must be > 0");
  if (eyes.empty()) throw InvalidArgument(at + "no eyes (one camera at least)");
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
