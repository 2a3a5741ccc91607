// solview's presenter: the window's Vulkan surface and swapchain, and the
// commands that put one frame of the march kernel on the screen. It knows
// nothing of scenes, input or the render scale's policy (solview.cpp).
//
// Two paths (docs/solview.md "How solview presents a frame"):
//  - direct: at render scale 1 the kernel writes straight into the swapchain
//    image (a storage-capable UNORM image, through the display and
//    sRGB-encoded by the kernel);
//  - blit: a scaled frame goes to an RGBA32F image (shown through the
//    display into a second one by vk::DisplayPass where the display is not
//    the default), then a blit scales it into an sRGB swapchain image, which
//    encodes it.
// Each path has its own swapchain; a change of path re-creates it. Two frames
// are in flight: present() records frame n while the device may still run
// frame n - 1; it waits only for frame n - 2's fence (its slot's), the
// swapchain's acquire and, with vsync, the presentation engine.
#pragma once

#include <GLFW/glfw3.h>  // after vulkan_core.h (GLFW_INCLUDE_VULKAN is defined by CMake)

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <sol/camera.hpp>
#include <sol/vk/buffer.hpp>
#include <sol/vk/context.hpp>
#include <sol/vk/display.hpp>
#include <sol/vk/frame_timer.hpp>
#include <sol/vk/image.hpp>
#include <sol/vk/march.hpp>

#include "frame_stats.hpp"

namespace sol::viewer {

/// Frames the presenter keeps in flight. The renderer it is given must
/// allow one more (MarchOptions::frames_in_flight = kFramesInFlight + 1):
/// a synchronous render() between two frames (solview's steps probe) then
/// never rebinds a descriptor set that a pending frame uses.
inline constexpr int kFramesInFlight = 2;

/// What draws over a frame (solview's overlay panel): records its commands
/// on the swapchain image's view, which is in COLOR_ATTACHMENT_OPTIMAL, of
/// the given format and size, and leaves it there.
struct OverlayDraw {
  std::function<void(VkCommandBuffer, VkImageView, VkFormat, std::uint32_t width, std::uint32_t height)> record;
  bool in_capture = false;  ///< screenshots and --record take the frame with it (else without)
};

class Presenter {
 public:
  /// The surface of `window`, the command buffer and synchronisation, and a
  /// first swapchain (for the direct path when `allow_direct` and
  /// `start_direct`). Throws std::runtime_error when the device cannot
  /// present to the window.
  Presenter(vk::Context& context, GLFWwindow* window, bool vsync, bool allow_direct, bool start_direct);
  ~Presenter();
  Presenter(const Presenter&) = delete;
  Presenter& operator=(const Presenter&) = delete;

  /// Re-creates the swapchain: after a resize, a vsync change, or when
  /// out_of_date(). Leaves none while the window has no size (minimised).
  void recreate(bool vsync);
  /// Whether a swapchain exists to present to.
  bool ready() const { return m_swapchain != VK_NULL_HANDLE; }
  /// The last present found the swapchain out of date or suboptimal: recreate() it.
  bool out_of_date() const { return m_out_of_date; }
  VkExtent2D extent() const { return m_extent; }
  /// The swapchain's format (it changes with the path).
  VkFormat format() const { return m_format; }
  /// Whether the swapchain images can be drawn to (present's overlay).
  bool overlay_capable() const { return m_overlay_capable; }

  /// Waits until every frame's commands are done (before the host reads
  /// what they wrote, such as a capture).
  void wait_for_frame();

  /// What present() did.
  struct Shown {
    bool direct = false;         ///< the kernel wrote the swapchain image itself
    double record_ms = 0.0;      ///< host time to record the frame (renderer.record and the commands)
    bool rendered = true;        ///< the kernel ran (false: a finished accumulation shown again, FrameOptions::reuse)
  };
  /// How present() makes its frame.
  struct FrameOptions {
    bool capture = false;  ///< keep the frame as shown for save()
    bool vsync = true;
    const OverlayDraw* overlay = nullptr;  ///< drawn over the frame when given and overlay_capable()
    /// Accumulate: the kernel takes this sample of every pixel into the
    /// running mean in the blit path's image (progressive anti-aliasing;
    /// forces the blit path). None: one sample at the centres, overwriting.
    std::optional<vk::PixelSample> sample;
    /// Show the blit path's image as it is (a finished accumulation): no
    /// kernel; falls back to rendering when that image is not of this size.
    bool reuse = false;
    /// The display period the frame must fit (stats(): a frame whose device
    /// work and recording exceed it is missed), milliseconds.
    double period_ms = 1000.0 / 60.0;
    /// How the linear frame is shown: exposure and tone curve, as
    /// solrender's 8-bit files (the kernel applies it on the direct path, a
    /// display pass before the blit otherwise).
    Display display{};
  };
  /// Renders `eyes` side by side, each eye_width × eye_height, with
  /// `renderer` (its world set) and presents the frame, scaled to the
  /// window. With `capture` the frame as shown is also kept for save().
  /// nullopt when no frame was presented (the swapchain went out of date or
  /// the window was minimised meanwhile): try again after recreate().
  std::optional<Shown> present(vk::MarchRenderer& renderer, std::span<const Camera> eyes, int eye_width,
                               int eye_height, const FrameOptions& options);

  /// Writes the last frame presented: as shown (the swapchain image, when
  /// the surface lets it be copied and it was captured), else as rendered
  /// (before scaling). Waits for the frame. Throws std::runtime_error when
  /// there is none.
  void save(const std::string& path);

  /// Whether the surface offers the direct path.
  bool direct_capable() const { return m_direct_capable; }

  /// The rendered frames' figures so far (FrameStats: the interval between
  /// frames' ends and each frame's work from device timestamps, the host's
  /// recording); frames still in flight are counted once done
  /// (wait_for_frame counts them all). A frame shown again without the
  /// kernel is not counted and breaks the chain of intervals.
  const programs::FrameStats& stats() const { return m_stats; }

 private:
  /// One frame's resources: frame n uses slot n mod kFramesInFlight.
  struct Slot {
    VkCommandBuffer commands = VK_NULL_HANDLE;
    VkFence done = VK_NULL_HANDLE;            // created signalled: no frame yet
    VkSemaphore acquired = VK_NULL_HANDLE;    // the swapchain image's acquire
    std::optional<vk::FrameTimer> timer;      // timestamps before the first command and after the last
    bool pending = false;                     // a rendered frame whose figures are not yet counted
    bool follows = false;                     // it came right after a counted frame
    double record_ms = 0, period_ms = 0;
    long frame = -1;                          // the frame it holds (-1: none)
  };
  // Waits for the slot's frame and counts its figures.
  void retire(Slot& slot);
  void release() noexcept;
  void create_swapchain(bool vsync);
  void destroy_swapchain();
  void record_blit(VkCommandBuffer cb, VkImage swap_image, int render_w, int render_h, const Display& display, bool nearest);
  void write_capture(const std::string& path) const;
  void write_rendered(const std::string& path) const;

  vk::Context& m_context;
  GLFWwindow* m_window;
  bool m_allow_direct;
  VkSurfaceKHR m_surface = VK_NULL_HANDLE;
  VkSwapchainKHR m_swapchain = VK_NULL_HANDLE;
  VkFormat m_format = VK_FORMAT_UNDEFINED;
  VkExtent2D m_extent{};
  std::vector<VkImage> m_images;
  // One per swapchain image: the direct path's storage target, the overlay's colour attachment.
  std::vector<VkImageView> m_views;
  bool m_overlay_capable = false;  // the images have COLOR_ATTACHMENT usage
  // The direct path needs a UNORM format (sRGB formats are never storage-
  // capable; the kernel sRGB-encodes) with STORAGE and TRANSFER_SRC usage
  // (screenshots then always take the frame as shown).
  bool m_prefer_direct = false;   // the next swapchain is for the direct path when the surface allows it
  bool m_direct_capable = false;  // the surface allows it (known after create_swapchain)
  bool m_direct = false;          // the current swapchain is the direct path's
  bool m_out_of_date = false;
  std::vector<VkSemaphore> m_rendered;  // one per swapchain image: present waits on it
  VkCommandPool m_pool = VK_NULL_HANDLE;
  Slot m_slots[kFramesInFlight];
  long m_frames = 0;  // frames submitted
  programs::FrameStats m_stats;
  std::optional<std::uint64_t> m_last_end;  // the last counted frame's end (a device timestamp)
  bool m_chain = false;                 // the next frame follows a counted one
  bool m_linear_blit = false;
  bool m_can_capture = false;  // swapchain images may be copied out (TRANSFER_SRC)
  // The blit path's image: the kernel's output at the render scale. One
  // for all frames (they run in turn on the device, and an accumulation
  // reads the last one's); a replaced one is kept until the frames that
  // may read it are done: (the last frame that may, image).
  std::optional<vk::StorageImage> m_target;
  // The blit path's image as shown (a display that is not the default:
  // DisplayPass), the size of m_target, and the pass.
  std::optional<vk::StorageImage> m_shown;
  std::optional<vk::DisplayPass> m_display_pass;
  Display m_display{};  // the last frame's (write_rendered)
  std::vector<std::pair<long, vk::StorageImage>> m_retired_targets;
  int m_rendered_w = 0, m_rendered_h = 0;  // of the image in m_target (both eyes)
  bool m_target_has_frame = false;         // m_target holds the last frame presented
  // The shown frame copied to the host (screenshots, --record).
  std::optional<vk::Buffer> m_capture;
  std::uint32_t m_captured_w = 0, m_captured_h = 0;  // of the frame in m_capture (0: none)
  VkFormat m_captured_format = VK_FORMAT_UNDEFINED;
  bool m_captured_direct = false;
};

}  // namespace sol::viewer
