// solview's overlay: Dear ImGui on the viewer's window, drawn over the
// frame on the swapchain image. The platform side is ImGui's GLFW backend,
// the drawing its Vulkan backend (both compiled from the sources Debian's
// libimgui-dev ships among its examples). What the panel shows is
// panel.cpp's; this class only runs ImGui's frames and records its draws.
#pragma once

#include <GLFW/glfw3.h>  // after vulkan_core.h (GLFW_INCLUDE_VULKAN is defined by CMake)

#include <cstdint>
#include <vector>

#include <sol/vk/context.hpp>

namespace sol::viewer {

class Overlay {
 public:
  /// ImGui's context and its GLFW backend on `window`. Call after the
  /// application installed its own GLFW callbacks: ImGui's chain to them.
  Overlay(vk::Context& context, GLFWwindow* window);
  ~Overlay();
  Overlay(const Overlay&) = delete;
  Overlay& operator=(const Overlay&) = delete;

  /// Starts ImGui's frame (input, display size) for a swapchain of
  /// `format` (the backend is built for it first when needed); build
  /// windows after it. Between frames only (the previous frame done).
  void begin_frame(VkFormat format);
  /// Ends it: the draw lists for record().
  void end_frame();
  /// Whether ImGui takes the mouse or the keyboard now (a slider being
  /// dragged, a text field in focus): the viewer's controls then leave them.
  bool wants_mouse() const;
  bool wants_keyboard() const;

  /// Records the last end_frame()'s draws over `view` (a swapchain image of
  /// `format`, in COLOR_ATTACHMENT_OPTIMAL, left there) in a render pass
  /// that keeps the frame under them. When the swapchain's format changed
  /// since begin_frame (the presenter switched paths) it draws nothing this
  /// frame: the backend is rebuilt at the next begin_frame.
  void record(VkCommandBuffer command_buffer, VkImageView view, VkFormat format, std::uint32_t width,
              std::uint32_t height);

 private:
  void build_backend(VkFormat format);
  void destroy_backend();

  vk::Context& m_context;
  VkDescriptorPool m_pool = VK_NULL_HANDLE;
  VkRenderPass m_render_pass = VK_NULL_HANDLE;
  VkFormat m_format = VK_FORMAT_UNDEFINED;  // of m_render_pass and the backend's pipeline
  bool m_backend = false;
  // The framebuffer of the frame in flight: destroyed at the next record()
  // (the frame is done by then) or with the overlay.
  // One per frame in flight, taken in turn: the one a call replaces was
  // recorded kFramesInFlight calls before, into a frame that is done.
  std::vector<VkFramebuffer> m_framebuffers;
  std::size_t m_next_framebuffer = 0;
};

}  // namespace sol::viewer
