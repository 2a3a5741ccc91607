// The denoiser on the device (not installed): MarchRenderer::denoise's
// work, the filter of sol/denoise.h in shaders/denoise.comp.
#pragma once

#include <sol/renderer.hpp>

#include "sol/vk/pipeline.hpp"

namespace sol::vk::detail {

class DenoiseFilter {
 public:
  explicit DenoiseFilter(Context& context);
  /// Replaces the colour of `image`, which the caller has checked
  /// (sol::validate_denoise), by the filter's, computed on the device;
  /// returns the device's time in ms.
  double run(RenderResult& image, int eyes);

 private:
  Context& m_context;
  ComputePipeline m_pipeline;
};

}  // namespace sol::vk::detail
