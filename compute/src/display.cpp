#include "sol/vk/display.hpp"

#include <string>

#include <sol/error.hpp>

#include "sol/vk/image.hpp"
#include "sol/vk/pipeline.hpp"

namespace sol::vk {
namespace {
#include "shaders/display_comp_spv.hpp"

// display.comp's push constants.
struct Push {
  std::int32_t width, height;
  float scale;
  std::int32_t tone;
};
static_assert(sizeof(Push) == 16, "display.comp's push block");
}  // namespace

struct DisplayPass::Impl {
  ComputePipeline pipeline;
};

DisplayPass::DisplayPass(Context& context, std::uint32_t frames_in_flight)
    : m_impl(std::make_unique<Impl>(Impl{ComputePipeline(context, {.name = "display",
                                                                   .spirv = display_comp_spv,
                                                                   .validated = true,
                                                                   .bindings = {{0, DescriptorType::StorageImage},
                                                                                {1, DescriptorType::StorageImage}},
                                                                   .push_constant_size = sizeof(Push),
                                                                   .descriptor_sets = frames_in_flight})})) {}

DisplayPass::~DisplayPass() = default;

void DisplayPass::record(VkCommandBuffer command_buffer, const StorageImage& linear, const StorageImage& shown, int width,
                         int height, const Display& display, std::uint32_t slot) {
  validate(display);
  ComputePipeline& p = m_impl->pipeline;
  if (slot >= p.descriptor_sets()) {
    throw InvalidArgument("sol::vk::DisplayPass: slot " + std::to_string(slot) + " of " + std::to_string(p.descriptor_sets()));
  }
  const auto w = static_cast<std::uint32_t>(width), h = static_cast<std::uint32_t>(height);
  if (width < 1 || height < 1 || linear.width() < w || linear.height() < h || shown.width() < w || shown.height() < h) {
    throw InvalidArgument("sol::vk::DisplayPass: the images must hold " + std::to_string(width) + " x " +
                          std::to_string(height) + " pixels");
  }
  p.bind(0, linear, slot);
  p.bind(1, shown, slot);
  const Push push{width, height, static_cast<float>(display.scale()), static_cast<std::int32_t>(display.tone)};
  p.record_dispatch(command_buffer, group_count(w, 8), group_count(h, 8), std::as_bytes(std::span(&push, 1)), slot);
}

}  // namespace sol::vk
