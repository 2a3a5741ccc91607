#include "device_frames.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <sol/vk/error.hpp>
#include <sol/vk/pipeline.hpp>

namespace sol::xr {
namespace {

double now_ms() {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// A level's rectangle in an eye image of width x height: centred on the
/// centre of view (cx, cy) and moved inside the image.
struct PixelRect {
  int x0, y0, x1, y1;
};
PixelRect fovea_rect(const FoveaLevel& level, double cx, double cy, int width, int height) {
  const int w = std::max(1, static_cast<int>(std::lround(level.extent * width)));
  const int h = std::max(1, static_cast<int>(std::lround(level.extent * height)));
  const int x0 = std::clamp(static_cast<int>(std::lround(cx - 0.5 * w)), 0, width - w);
  const int y0 = std::clamp(static_cast<int>(std::lround(cy - 0.5 * h)), 0, height - h);
  return {x0, y0, x0 + w, y0 + h};
}

// An eye's window widened by one pixel of an rw x rh image on every side.
// Rendered at (rw + 2) x (rh + 2), the image holds a ring of the scene's
// own pixels around the rw x rh inside, so that a linear blit of that
// inside (a blit's filter clamps to the whole image, not to its region)
// reads no texel the kernel did not write, nor the other eye's.
Camera widened_by_a_pixel(const Camera& eye, int rw, int rh) {
  const glm::dvec4 w = image_window(eye, rw, rh);  // left, right, top, bottom
  const double dx = (w.y - w.x) / rw, dy = (w.z - w.w) / rh;
  Camera wide = eye;
  wide.frustum = Frustum{w.x - dx, w.y + dx, w.w - dy, w.z + dy};
  return wide;
}

std::array<Camera, 2> widened_by_a_pixel(const std::array<Camera, 2>& eyes, int rw, int rh) {
  return {widened_by_a_pixel(eyes[0], rw, rh), widened_by_a_pixel(eyes[1], rw, rh)};
}

/// The blit region of eye v's rw x rh inside in an image of both eyes side
/// by side (the left eye on the left), each rendered with a border of
/// `border` pixels (1: widened_by_a_pixel; 0: none), (rw + 2 border) x (rh + 2 border).
VkImageBlit eye_region(std::size_t v, int rw, int rh, int border) {
  VkImageBlit region{};
  region.srcSubresource = region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  const auto x0 = static_cast<std::int32_t>(v) * (rw + 2 * border) + border;
  region.srcOffsets[0] = {x0, border, 0};
  region.srcOffsets[1] = {x0 + rw, rh + border, 1};
  return region;
}

}  // namespace

void begin_transfer_to(VkCommandBuffer cmd, VkImage target) {
  vk::image_barrier(cmd, target, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT,
                    VK_ACCESS_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
}

void end_transfer_to(VkCommandBuffer cmd, VkImage target) {
  vk::image_barrier(cmd, target, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                    VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                    VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                    VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
}

DeviceFrames::DeviceFrames(vk::Context& context, vk::MarchRenderer& renderer, std::uint32_t width, std::uint32_t height,
                           bool foveation)
    : m_context(context),
      m_renderer(renderer),
      m_width(width),
      m_height(height),
      m_rendered(context, 2 * (width + 2), height + 2) {  // (room for the border of a scaled frame's eyes)
  try {
    VkFormatProperties props{};
    vkGetPhysicalDeviceFormatProperties(m_context.physical_device(), VK_FORMAT_R32G32B32A32_SFLOAT, &props);
    m_linear_blit = (props.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT) != 0;
    const VkDevice vk_device = m_context.device();
    for (int k = 0; k < kFramesInFlight; ++k) {
      Slot& slot = m_slots.emplace_back();
      VkCommandPoolCreateInfo pool{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO, nullptr,
                                   VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT, m_context.queue_family_index()};
      vk::check(vkCreateCommandPool(vk_device, &pool, nullptr, &slot.pool), "vkCreateCommandPool");
      VkCommandBufferAllocateInfo allocate{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, nullptr, slot.pool,
                                           VK_COMMAND_BUFFER_LEVEL_PRIMARY, 1};
      vk::check(vkAllocateCommandBuffers(vk_device, &allocate, &slot.commands), "vkAllocateCommandBuffers");
      VkFenceCreateInfo fence{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO, nullptr, VK_FENCE_CREATE_SIGNALED_BIT};
      vk::check(vkCreateFence(vk_device, &fence, nullptr, &slot.done), "vkCreateFence");
      slot.timer.emplace(m_context);
    }
    if (foveation) {
      for (const FoveaLevel& level : kFoveation) {
        // (Rounding, and a border of a pixel each side: widened_by_a_pixel.)
        const auto w = static_cast<std::uint32_t>(std::ceil(level.extent * level.scale * width)) + 3;
        const auto h = static_cast<std::uint32_t>(std::ceil(level.extent * level.scale * height)) + 3;
        m_fovea.emplace_back(m_context, 2 * w, h);
      }
    }
    // The deferred passes' lists for a stereo frame, allocated now rather than in the first frame.
    m_renderer.reserve(static_cast<int>(width), static_cast<int>(height), 2);
  } catch (...) {
    release();
    throw;
  }
}

DeviceFrames::~DeviceFrames() { release(); }

void DeviceFrames::release() noexcept {
  vkDeviceWaitIdle(m_context.device());  // nothing of ours may still run
  const VkDevice device = m_context.device();
  for (Slot& slot : m_slots) {
    if (slot.done != VK_NULL_HANDLE) vkDestroyFence(device, slot.done, nullptr);
    if (slot.pool != VK_NULL_HANDLE) vkDestroyCommandPool(device, slot.pool, nullptr);  // frees its buffer
  }
  m_slots.clear();
}

bool DeviceFrames::retire(long frame, FrameClock& clock) {
  Slot& slot = m_slots[static_cast<std::size_t>(frame % kFramesInFlight)];
  vk::check(vkWaitForFences(m_context.device(), 1, &slot.done, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  if (!slot.pending) return false;
  slot.pending = false;
  // The work and the interval on the device's clock; without timestamps the
  // interval between submissions on the host's, and no work.
  double work_ms = 0.0;
  std::optional<double> interval;
  if (const std::optional<vk::FrameTimer::Reading> t = slot.timer->read()) {
    work_ms = slot.timer->elapsed_ms(t->begin, t->end);
    if (slot.follows && clock.last_end) interval = slot.timer->elapsed_ms(*clock.last_end, t->end);
    clock.last_end = t->end;
  } else {
    if (slot.follows && clock.last_end_ms) interval = slot.submitted_ms - *clock.last_end_ms;
    clock.last_end_ms = slot.submitted_ms;
  }
  clock.stats.add(interval, work_ms, slot.record_ms, slot.period_ms);
  clock.scale_sum += slot.scale;
  clock.last_work_ms = work_ms + slot.record_ms;
  clock.last_adaptive = slot.adaptive;
  return true;
}

void DeviceFrames::drain(long frames, FrameClock& clock) {
  for (long k = 0; k < kFramesInFlight; ++k) retire(frames + k, clock);
}

/// The plain frame: both eyes in one dispatch, then a blit per eye.
void DeviceFrames::record_eyes(VkCommandBuffer cmd, const std::array<Camera, 2>& cameras, const std::vector<VkImage>& targets,
                               const FramePlan& plan) {
  const std::uint32_t width = m_width, height = m_height;
  const vk::StorageImage& rendered = m_rendered;
  // Each eye at the plan's scale (the image's top-left 2 rw x rh; scaled,
  // with a border of a pixel each side, widened_by_a_pixel, as the linear
  // blit reads one beyond its region); a refinement sample (at full size)
  // joins the running mean already there; a finished refinement is shown
  // again without the kernel.
  const int rw = std::max(1, static_cast<int>(std::lround(width * plan.scale)));
  const int rh = std::max(1, static_cast<int>(std::lround(height * plan.scale)));
  const auto w = static_cast<std::int32_t>(width), h = static_cast<std::int32_t>(height);
  const bool scaled = rw != w || rh != h;
  if (!plan.reuse) {
    if (scaled) {
      m_renderer.record(cmd, widened_by_a_pixel(cameras, rw, rh), rw + 2, rh + 2, rendered);
    } else {
      m_renderer.record(cmd, cameras, rw, rh, rendered, plan.sample.value_or(vk::PixelSample{}));
    }
  }
  // The kernel's writes must land before the blits read them, from the
  // layout made for reading by transfers (GENERAL costs some devices a
  // slower path, which the validation layers point out).
  vk::image_barrier(cmd, rendered.handle(), VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                         VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT, VK_IMAGE_LAYOUT_GENERAL,
                         VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  for (std::size_t v = 0; v < targets.size(); ++v) {
    begin_transfer_to(cmd, targets[v]);
    VkImageBlit region = eye_region(v, rw, rh, scaled ? 1 : 0);  // (1:1, by the nearest texel: no border)
    region.dstOffsets[1] = {w, h, 1};
    vkCmdBlitImage(cmd, rendered.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, targets[v],
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region,
                   scaled && m_linear_blit ? VK_FILTER_LINEAR : VK_FILTER_NEAREST);
    end_transfer_to(cmd, targets[v]);
  }
  // The next frame's kernel writes the image again (GENERAL, as the kernel
  // takes it) only after these blits have read it.
  vk::image_barrier(cmd, rendered.handle(), VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT,
                         VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                         VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL);
}

/// The foveated frame (kFoveation): per level one dispatch of both eyes,
/// each with the window of its rectangle, at the level's resolution times
/// the render scale; then per eye the levels blitted into the swapchain
/// image from the outside in, each over the last.
void DeviceFrames::record_foveated(VkCommandBuffer cmd, const std::array<Camera, 2>& cameras,
                                   const std::vector<VkImage>& targets, double scale) {
  const std::uint32_t width = m_width, height = m_height;
  const int w = static_cast<int>(width), h = static_cast<int>(height);
  PixelRect rects[kFoveaLevels][2];
  int sizes[kFoveaLevels][2];
  for (int l = 0; l < kFoveaLevels; ++l) {
    std::array<Camera, 2> level = cameras;
    for (std::size_t v = 0; v < 2; ++v) {
      const Frustum f = cameras[v].frustum.value_or(Frustum{});
      // The centre of view (tangent 0, 0) in pixels, rows from the top.
      const double cx = std::clamp(w * (0.0 - f.left) / (f.right - f.left), 0.0, static_cast<double>(w));
      const double cy = std::clamp(h * (f.up - 0.0) / (f.up - f.down), 0.0, static_cast<double>(h));
      const PixelRect r = fovea_rect(kFoveation[l], cx, cy, w, h);
      rects[l][v] = r;
      auto tx = [&](int px) { return f.left + (f.right - f.left) * px / w; };
      auto ty = [&](int py) { return f.up - (f.up - f.down) * py / h; };
      level[v].frustum = Frustum{tx(r.x0), tx(r.x1), ty(r.y1), ty(r.y0)};
    }
    const double resolution = kFoveation[l].scale * scale;
    sizes[l][0] = std::max(1, static_cast<int>(std::lround((rects[l][0].x1 - rects[l][0].x0) * resolution)));
    sizes[l][1] = std::max(1, static_cast<int>(std::lround((rects[l][0].y1 - rects[l][0].y0) * resolution)));
    // With a border (widened_by_a_pixel): the levels' blits filter linearly.
    m_renderer.record(cmd, widened_by_a_pixel(level, sizes[l][0], sizes[l][1]), sizes[l][0] + 2, sizes[l][1] + 2,
                      m_fovea[static_cast<std::size_t>(l)]);
  }
  for (const vk::StorageImage& image : m_fovea) {
    vk::image_barrier(cmd, image.handle(), VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                           VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT, VK_IMAGE_LAYOUT_GENERAL,
                           VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  }
  for (std::size_t v = 0; v < targets.size(); ++v) {
    begin_transfer_to(cmd, targets[v]);
    for (int l = 0; l < kFoveaLevels; ++l) {
      if (l > 0) {  // each level over the last: its blit waits for theirs (write after write)
        vk::image_barrier(cmd, targets[v], VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                               VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                               VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
      }
      const PixelRect& r = rects[l][v];
      const int lw = sizes[l][0], lh = sizes[l][1];
      VkImageBlit region = eye_region(v, lw, lh, 1);
      region.dstOffsets[0] = {r.x0, r.y0, 0};
      region.dstOffsets[1] = {r.x1, r.y1, 1};
      const bool scaled = lw != r.x1 - r.x0 || lh != r.y1 - r.y0;
      vkCmdBlitImage(cmd, m_fovea[static_cast<std::size_t>(l)].handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                     targets[v], VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region,
                     scaled && m_linear_blit ? VK_FILTER_LINEAR : VK_FILTER_NEAREST);
    }
    end_transfer_to(cmd, targets[v]);
  }
  for (const vk::StorageImage& image : m_fovea) {
    vk::image_barrier(cmd, image.handle(), VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT,
                           VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                           VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL);
  }
}

void DeviceFrames::submit(long frame, const std::array<Camera, 2>& cameras, const std::vector<VkImage>& targets,
                          const FramePlan& plan, bool follows, double period_ms, bool adaptive) {
  Slot& slot = m_slots[static_cast<std::size_t>(frame % kFramesInFlight)];
  const double begin = now_ms();
  const VkCommandBuffer cmd = slot.commands;
  vk::check(vkResetFences(m_context.device(), 1, &slot.done), "vkResetFences");
  vk::check(vkResetCommandBuffer(cmd, 0), "vkResetCommandBuffer");
  VkCommandBufferBeginInfo info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO, nullptr,
                                VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT, nullptr};
  vk::check(vkBeginCommandBuffer(cmd, &info), "vkBeginCommandBuffer");
  slot.timer->begin(cmd);
  if (plan.foveated) {
    record_foveated(cmd, cameras, targets, plan.scale);
  } else {
    record_eyes(cmd, cameras, targets, plan);
  }
  slot.timer->end(cmd);
  vk::check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
  VkSubmitInfo submit{};
  submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd;
  vk::check(vkQueueSubmit(m_context.queue(), 1, &submit, slot.done), "vkQueueSubmit");
  slot.submitted_ms = now_ms();
  slot.record_ms = slot.submitted_ms - begin;
  slot.pending = true;
  slot.follows = follows;
  slot.period_ms = period_ms;
  slot.adaptive = adaptive;
  slot.scale = plan.reuse ? 1.0 : plan.scale;
}

}  // namespace sol::xr
