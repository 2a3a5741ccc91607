#include "denoise_filter.hpp"

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec4.hpp>
#include <sol/denoise.h>
#include <sol/denoise.hpp>

#include "sol/vk/buffer.hpp"

namespace sol::vk::detail {
namespace {
#include "shaders/denoise_comp_spv.hpp"

// denoise.comp's push constants.
struct Push {
  std::int32_t width, height, eye_width, mode, step, clamp;
};
static_assert(sizeof(Push) == 24, "denoise.comp's push block");

ComputePipelineDesc describe() {
  ComputePipelineDesc d{.name = "denoise", .spirv = denoise_comp_spv, .validated = true};
  for (std::uint32_t b = 0; b < 7; ++b) d.bindings.push_back({b, DescriptorType::StorageBuffer});
  d.push_constant_size = sizeof(Push);
  return d;
}

}  // namespace

DenoiseFilter::DenoiseFilter(Context& context) : m_context(context), m_pipeline(context, describe()) {}

double DenoiseFilter::run(RenderResult& image, int eyes) {
  const std::size_t n = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
  std::vector<glm::vec4> normals(n), albedos(n);
  // The device filters the colour less the emission (sol/denoise.h); the
  // emission is added back to what it reads back.
  std::vector<float> rgba = image.rgba;
  for (std::size_t k = 0; k < n; ++k) {
    for (std::size_t c = 0; c < 3; ++c) rgba[4 * k + c] -= image.emission[3 * k + c];
    normals[k] = glm::vec4(image.normal[3 * k], image.normal[3 * k + 1], image.normal[3 * k + 2], image.distance[k]);
    albedos[k] = glm::vec4(image.albedo[3 * k], image.albedo[3 * k + 1], image.albedo[3 * k + 2], image.object[k]);
  }
  const VkDeviceSize vec4s = n * sizeof(glm::vec4);
  Buffer color(m_context, vec4s), normal(m_context, vec4s), albedo(m_context, vec4s);
  Buffer slopes(m_context, n * sizeof(float), BufferUsage::DeviceStorage);
  std::array<Buffer, 2> light{Buffer(m_context, vec4s, BufferUsage::DeviceStorage),
                              Buffer(m_context, vec4s, BufferUsage::DeviceStorage)};
  // Each pixel's own noise, from its samples' light moment (sol::own_variances;
  // -1 throughout for an image without: the device takes the neighbours').
  std::vector<float> own(n, -1.0f);
  const std::vector<double> owns = own_variances(image);
  for (std::size_t k = 0; k < owns.size(); ++k) own[k] = static_cast<float>(owns[k]);
  Buffer noise(m_context, n * sizeof(float));
  color.write(rgba);
  normal.write(normals);
  albedo.write(albedos);
  noise.write(own);
  m_pipeline.bind(0, color);
  m_pipeline.bind(1, normal);
  m_pipeline.bind(2, albedo);
  m_pipeline.bind(3, slopes);
  m_pipeline.bind(6, noise);
  const std::uint32_t gx = group_count(static_cast<std::uint32_t>(image.width), 8);
  const std::uint32_t gy = group_count(static_cast<std::uint32_t>(image.height), 8);
  const bool clamp = !owns.empty() && image.samples >= kernel::kDenoiseClampSamples;  // (as sol::denoise)
  Push push{image.width, image.height, image.width / eyes, 0, 1, clamp ? 1 : 0};
  // Each dispatch reads the light the one before wrote: `in` and `out` swap.
  int in = 1;
  auto dispatch = [&](int mode, int step) {
    m_pipeline.bind(4, light[static_cast<std::size_t>(in)]);
    m_pipeline.bind(5, light[static_cast<std::size_t>(1 - in)]);
    push.mode = mode;
    push.step = step;
    const double ms = m_pipeline.run(gx, gy, push);
    in = 1 - in;
    return ms;
  };
  double ms = dispatch(0, 1);
  for (int pass = 0; pass < kernel::kDenoisePasses; ++pass) ms += dispatch(1, 1 << pass);
  ms += dispatch(2, 1);
  color.read(image.rgba);
  for (std::size_t k = 0; k < n; ++k) {
    for (std::size_t c = 0; c < 3; ++c) image.rgba[4 * k + c] += image.emission[3 * k + c];
  }
  return ms;
}

}  // namespace sol::vk::detail
