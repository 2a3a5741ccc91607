// The display of a linear image on the device: the exposure and tone curve
// (sol/display.hpp) that solrender's 8-bit files and MarchRenderer's
// UnormTarget apply, for a presenter that shows a float image through a
// blit into an sRGB swapchain image (the blit encodes; this pass shows).
#pragma once

#include <cstdint>
#include <memory>

#include <vulkan/vulkan_core.h>
#include <sol/display.hpp>

namespace sol::vk {

class Context;
class StorageImage;

class DisplayPass {
 public:
  /// Its pipeline, with a descriptor set for each of `frames_in_flight`
  /// frames (the slots record() takes).
  DisplayPass(Context& context, std::uint32_t frames_in_flight);
  ~DisplayPass();
  DisplayPass(const DisplayPass&) = delete;
  DisplayPass& operator=(const DisplayPass&) = delete;

  /// Records the pass: pixels [0, width) × [0, height) of `linear` (RGBA32F,
  /// in GENERAL layout) shown through `display` into `shown` (RGBA32F, at
  /// least as large, GENERAL), alpha kept. No barrier is recorded: the
  /// caller orders the dispatch after what wrote `linear` and before what
  /// reads `shown`. `slot` (below frames_in_flight) names the descriptor
  /// set, which no pending command buffer may use. Throws InvalidArgument
  /// for a bad display, slot or size.
  void record(VkCommandBuffer command_buffer, const StorageImage& linear, const StorageImage& shown, int width,
              int height, const Display& display, std::uint32_t slot);

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

}  // namespace sol::vk
