// solxr's work on the device, frame by frame: the ring of frames in flight
// (a command buffer, a fence and two timestamps a slot), both eyes in one
// dispatch and one submission blitted into their swapchain images, the
// render scale and refinement a frame is recorded at, the foveation's
// levels, and the figures each frame's slot gives when it comes back. The
// OpenXR session around it is solxr.cpp's.
#pragma once

#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include <sol/camera.hpp>
#include <sol/vk/context.hpp>
#include <sol/vk/frame_timer.hpp>
#include <sol/vk/image.hpp>
#include <sol/vk/march.hpp>

#include "frame_stats.hpp"

namespace sol::xr {

/// Frames in flight: frame n is recorded into slot n mod kFramesInFlight
/// while the device may still run frame n - 1. A slot is reused once its
/// fence says its frame is done; with the runtime pacing the loop that
/// frame finished long before, so the wait returns at once.
inline constexpr int kFramesInFlight = 2;

/// What a frame renders: both eyes at `scale` of their size, or a
/// refinement sample at full size into the running mean, or the finished
/// refinement again (no kernel).
struct FramePlan {
  double scale = 1.0;
  std::optional<sol::vk::PixelSample> sample;
  bool reuse = false;
  bool foveated = false;  // the levels of kFoveation instead of one image per eye
};

/// Fixed foveated rendering (--foveation on): each eye in three levels
/// around its centre of view (where the view direction meets the image:
/// tangent 0, 0 of its window), each a rectangle of the eye image rendered
/// at its own resolution with the window of that rectangle, the outer
/// ones first: the whole eye at half resolution (a quarter of the rays), a
/// rectangle of 60 % of the eye's width and height at 1/sqrt 2 (half the
/// rays), and one of 35 % at full resolution. 0.25 + 0.36 / 2 + 0.35^2 =
/// 55 % of the rays of the full render.
struct FoveaLevel {
  double extent;  // of the eye's width and height
  double scale;   // the resolution within it
};
inline constexpr FoveaLevel kFoveation[] = {{1.0, 0.5}, {0.6, 0.7071067811865476}, {0.35, 1.0}};
inline constexpr int kFoveaLevels = 3;

/// The frames' figures, counted in frame order as their slots come back.
struct FrameClock {
  programs::FrameStats stats;
  double scale_sum = 0.0;  // the counted frames' render scales
  std::optional<std::uint64_t> last_end;  // the previous counted frame's end: a device timestamp
  std::optional<double> last_end_ms;      // or, without timestamps (and for the host copy), the host clock's
  bool chain = false;                 // the next frame follows a rendered one
  double last_work_ms = 0.0;          // the last counted frame's device work plus host recording
  bool last_adaptive = false;         // it was rendered at the adaptive scale
};

/// The swapchain image from UNDEFINED (its old contents are discarded: the
/// whole image is overwritten) to TRANSFER_DST, after the runtime's last read
/// of it (its compositor, any stage).
void begin_transfer_to(VkCommandBuffer cmd, VkImage target);
/// The swapchain image to COLOR_ATTACHMENT_OPTIMAL, the layout the runtime
/// expects released colour images in (XR_KHR_vulkan_enable2), with our
/// transfer write finished before it reads.
void end_transfer_to(VkCommandBuffer cmd, VkImage target);

/// The device copy's frames: one per display frame, recorded and submitted
/// without waiting, frame n on slot n mod kFramesInFlight.
class DeviceFrames {
 public:
  /// For eyes of width x height: the kernel's image of both eyes, the
  /// foveation levels' images when asked for, the ring's slots; the
  /// renderer's lists for a stereo frame reserved now rather than in the
  /// first frame. The renderer must keep kFramesInFlight frames in flight
  /// (times kFoveaLevels with foveation: a level is a call of its own).
  DeviceFrames(vk::Context& context, vk::MarchRenderer& renderer, std::uint32_t width, std::uint32_t height,
               bool foveation);
  /// Waits for the device, then destroys the slots.
  ~DeviceFrames();
  DeviceFrames(const DeviceFrames&) = delete;
  DeviceFrames& operator=(const DeviceFrames&) = delete;

  /// Waits for the frame that last used frame `frame`'s slot (frame -
  /// kFramesInFlight; done long before when the runtime paces the loop) and
  /// counts its figures into `clock`: its work between its two timestamps,
  /// its interval from the previous counted frame's end. Returns whether a
  /// frame was counted.
  bool retire(long frame, FrameClock& clock);
  /// Records frame `frame` on its slot (retire() it first) and submits it,
  /// not waited for, between two timestamps: the plan's frame (both eyes in
  /// one dispatch and a blit per eye into `targets`, converting to the
  /// swapchain's format and sRGB-encoding 8-bit sRGB ones; or the
  /// foveation's levels), signalling the slot's fence. `follows`: the frame
  /// right before was rendered (the interval counts); `adaptive`: rendered
  /// at the adaptive scale (its time steers it).
  void submit(long frame, const std::array<Camera, 2>& cameras, const std::vector<VkImage>& targets,
              const FramePlan& plan, bool follows, double period_ms, bool adaptive);
  /// After `frames` frames: those still in flight waited for and counted, in order.
  void drain(long frames, FrameClock& clock);

 private:
  /// One frame's resources on the ring.
  struct Slot {
  VkCommandPool pool = VK_NULL_HANDLE;
  VkCommandBuffer commands = VK_NULL_HANDLE;
  VkFence done = VK_NULL_HANDLE;            // the slot's frame is done (created signalled: no frame yet)
  std::optional<vk::FrameTimer> timer;      // timestamps before the frame's first command and after its last
  bool pending = false;                     // a frame was submitted whose figures are not yet counted
  bool follows = false;                     // that frame came right after a rendered frame
  double record_ms = 0, period_ms = 0;      // its host recording time and the display period it had
  double submitted_ms = 0;                  // the host clock at its submission (intervals without timestamps)
  bool adaptive = false;                    // rendered at the adaptive scale (its time steers the scale)
  double scale = 1.0;                       // its render scale
};
  void release() noexcept;
  void record_eyes(VkCommandBuffer cmd, const std::array<Camera, 2>& cameras, const std::vector<VkImage>& targets,
                   const FramePlan& plan);
  void record_foveated(VkCommandBuffer cmd, const std::array<Camera, 2>& cameras, const std::vector<VkImage>& targets,
                       double scale);

  vk::Context& m_context;
  vk::MarchRenderer& m_renderer;
  std::uint32_t m_width, m_height;
  vk::StorageImage m_rendered;          // both eyes side by side, the kernel's RGBA32F image
  std::vector<vk::StorageImage> m_fovea;  // with foveation: each level's image, both eyes side by side
  std::vector<Slot> m_slots;
  bool m_linear_blit = false;  // RGBA32F blits may filter linearly (scaled frames)
};

}  // namespace sol::xr
