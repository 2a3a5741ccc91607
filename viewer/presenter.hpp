// solview's presenter: the window's Vulkan surface and swapchain, and the
// commands that put one frame of the march kernel on the screen. It knows
// nothing of scenes, input or the render scale's policy (solview.cpp).
//
// Two paths (docs/solview.md "How solview presents a frame"):
//  - direct: at render scale 1 the kernel writes straight into the swapchain
//    image (a storage-capable UNORM image, sRGB-encoded by the kernel);
//  - blit: a scaled frame goes to an RGBA32F image, then a blit scales it
//    into an sRGB swapchain image, which encodes it.
// Each path has its own swapchain; a change of path re-creates it. One frame
// is in flight: present() waits for the previous frame before it records.
#pragma once

#include <GLFW/glfw3.h>  // after vulkan_core.h (GLFW_INCLUDE_VULKAN is defined by CMake)

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <sol/camera.hpp>
#include <sol/vk/buffer.hpp>
#include <sol/vk/context.hpp>
#include <sol/vk/image.hpp>
#include <sol/vk/march.hpp>

namespace sol::viewer {

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

  /// Waits until the previous frame's commands are done (before changing
  /// what they read, such as the renderer's world).
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

 private:
  void release() noexcept;
  void create_swapchain(bool vsync);
  void destroy_swapchain();
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
  VkSemaphore m_acquired = VK_NULL_HANDLE;
  VkFence m_frame_done = VK_NULL_HANDLE;
  VkCommandPool m_pool = VK_NULL_HANDLE;
  VkCommandBuffer m_commands = VK_NULL_HANDLE;
  bool m_linear_blit = false;
  bool m_can_capture = false;  // swapchain images may be copied out (TRANSFER_SRC)
  // The blit path's image: the kernel's output at the render scale.
  std::optional<vk::StorageImage> m_target;
  int m_rendered_w = 0, m_rendered_h = 0;  // of the image in m_target (both eyes)
  bool m_target_has_frame = false;         // m_target holds the last frame presented
  // The shown frame copied to the host (screenshots, --record).
  std::optional<vk::Buffer> m_capture;
  std::uint32_t m_captured_w = 0, m_captured_h = 0;  // of the frame in m_capture (0: none)
  VkFormat m_captured_format = VK_FORMAT_UNDEFINED;
  bool m_captured_direct = false;
};

}  // namespace sol::viewer
