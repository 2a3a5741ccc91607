#include "presenter.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include <sol/vk/error.hpp>

#include "image_file.hpp"

namespace sol::viewer {

Presenter::Presenter(vk::Context& context, GLFWwindow* window, bool vsync, bool allow_direct, bool start_direct)
    : m_context(context), m_window(window), m_allow_direct(allow_direct), m_prefer_direct(allow_direct && start_direct) {
  VkDevice device = context.device();
  try {
    vk::check(glfwCreateWindowSurface(context.instance(), window, nullptr, &m_surface), "glfwCreateWindowSurface");
    VkBool32 supported = VK_FALSE;
    vk::check(vkGetPhysicalDeviceSurfaceSupportKHR(context.physical_device(), context.queue_family_index(), m_surface,
                                                   &supported),
              "vkGetPhysicalDeviceSurfaceSupportKHR");
    if (!supported) throw std::runtime_error("the Vulkan device '" + context.device_name() + "' cannot present to this window");
    VkFormatProperties props{};
    vkGetPhysicalDeviceFormatProperties(context.physical_device(), VK_FORMAT_R32G32B32A32_SFLOAT, &props);
    if (!(props.optimalTilingFeatures & VK_FORMAT_FEATURE_BLIT_SRC_BIT)) {
      throw std::runtime_error("the Vulkan device cannot blit from RGBA32F images");
    }
    m_linear_blit = (props.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT) != 0;
    VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO, nullptr,
                                      VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT, context.queue_family_index()};
    vk::check(vkCreateCommandPool(device, &pool_info, nullptr, &m_pool), "vkCreateCommandPool");
    for (Slot& slot : m_slots) {
      VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, nullptr, m_pool,
                                        VK_COMMAND_BUFFER_LEVEL_PRIMARY, 1};
      vk::check(vkAllocateCommandBuffers(device, &alloc, &slot.commands), "vkAllocateCommandBuffers");
      VkSemaphoreCreateInfo sem{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO, nullptr, 0};
      vk::check(vkCreateSemaphore(device, &sem, nullptr, &slot.acquired), "vkCreateSemaphore");
      // Signalled: the slot's first wait returns at once.
      VkFenceCreateInfo fence{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO, nullptr, VK_FENCE_CREATE_SIGNALED_BIT};
      vk::check(vkCreateFence(device, &fence, nullptr, &slot.done), "vkCreateFence");
      slot.timer.emplace(context);
    }
    create_swapchain(vsync);
  } catch (...) {
    release();  // what was made so far: every handle is null or valid
    throw;
  }
}

Presenter::~Presenter() { release(); }

void Presenter::release() noexcept {
  VkDevice device = m_context.device();
  vkDeviceWaitIdle(device);
  destroy_swapchain();
  for (Slot& slot : m_slots) {
    if (slot.acquired) vkDestroySemaphore(device, slot.acquired, nullptr);
    if (slot.done) vkDestroyFence(device, slot.done, nullptr);
    slot = Slot{};
  }
  m_capture.reset();
  m_target.reset();
  m_retired_targets.clear();
  if (m_pool) vkDestroyCommandPool(device, m_pool, nullptr);
  m_pool = VK_NULL_HANDLE;
  if (m_surface) vkDestroySurfaceKHR(m_context.instance(), m_surface, nullptr);
  m_surface = VK_NULL_HANDLE;
}

void Presenter::create_swapchain(bool vsync) {
  VkPhysicalDevice gpu = m_context.physical_device();
  VkDevice device = m_context.device();
  VkSurfaceCapabilitiesKHR caps{};
  vk::check(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(gpu, m_surface, &caps), "vkGetPhysicalDeviceSurfaceCapabilitiesKHR");
  if (!(caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT)) {
    throw std::runtime_error("the surface's images cannot be blitted to (no TRANSFER_DST usage)");
  }
  std::uint32_t n = 0;
  vkGetPhysicalDeviceSurfaceFormatsKHR(gpu, m_surface, &n, nullptr);
  std::vector<VkSurfaceFormatKHR> formats(n);
  vkGetPhysicalDeviceSurfaceFormatsKHR(gpu, m_surface, &n, formats.data());
  if (formats.empty()) throw std::runtime_error("the surface offers no image formats");
  // An sRGB format: the blit encodes the kernel's linear colours as solrender's PNGs do.
  VkSurfaceFormatKHR chosen = formats[0];
  for (const VkSurfaceFormatKHR& f : formats) {
    if (f.format == VK_FORMAT_B8G8R8A8_SRGB || f.format == VK_FORMAT_R8G8B8A8_SRGB) {
      chosen = f;
      break;
    }
  }
  // The direct path's: a UNORM format the kernel can write, shown as sRGB.
  const VkImageUsageFlags direct_usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  m_direct_capable = false;
  for (const VkSurfaceFormatKHR& f : formats) {
    if ((caps.supportedUsageFlags & direct_usage) == direct_usage && f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR &&
        vk::MarchRenderer::can_write_unorm(m_context, f.format)) {
      m_direct_capable = true;
      if (m_prefer_direct) chosen = f;
      break;
    }
  }
  m_direct = m_direct_capable && m_prefer_direct;
  m_format = chosen.format;
  vkGetPhysicalDeviceSurfacePresentModesKHR(gpu, m_surface, &n, nullptr);
  std::vector<VkPresentModeKHR> modes(n);
  vkGetPhysicalDeviceSurfacePresentModesKHR(gpu, m_surface, &n, modes.data());
  VkPresentModeKHR mode = VK_PRESENT_MODE_FIFO_KHR;  // always there: vsync
  if (!vsync) {
    for (VkPresentModeKHR m : {VK_PRESENT_MODE_MAILBOX_KHR, VK_PRESENT_MODE_IMMEDIATE_KHR}) {
      if (std::find(modes.begin(), modes.end(), m) != modes.end()) mode = m;
    }
  }
  m_extent = caps.currentExtent;
  if (m_extent.width == 0xFFFFFFFFu) {
    int w = 0, h = 0;
    glfwGetFramebufferSize(m_window, &w, &h);
    m_extent.width = std::clamp(static_cast<std::uint32_t>(w), caps.minImageExtent.width, caps.maxImageExtent.width);
    m_extent.height = std::clamp(static_cast<std::uint32_t>(h), caps.minImageExtent.height, caps.maxImageExtent.height);
  }
  if (m_extent.width == 0 || m_extent.height == 0) {  // minimised: no swapchain until it has a size
    destroy_swapchain();
    return;
  }
  // An image for each frame in flight and one being shown.
  std::uint32_t count = std::max(caps.minImageCount, static_cast<std::uint32_t>(kFramesInFlight) + 1);
  if (caps.maxImageCount) count = std::min(count, caps.maxImageCount);
  VkSwapchainCreateInfoKHR info{};
  info.sType = VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR;
  info.surface = m_surface;
  info.minImageCount = count;
  info.imageFormat = chosen.format;
  info.imageColorSpace = chosen.colorSpace;
  info.imageExtent = m_extent;
  info.imageArrayLayers = 1;
  m_can_capture = (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT) != 0;
  m_overlay_capable = (caps.supportedUsageFlags & VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT) != 0;
  info.imageUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                    (m_can_capture ? VkImageUsageFlags{VK_IMAGE_USAGE_TRANSFER_SRC_BIT} : VkImageUsageFlags{0}) |
                    (m_overlay_capable ? VkImageUsageFlags{VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT} : VkImageUsageFlags{0}) |
                    (m_direct ? VkImageUsageFlags{VK_IMAGE_USAGE_STORAGE_BIT} : VkImageUsageFlags{0});
  info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.preTransform = caps.currentTransform;
  info.compositeAlpha = (caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR)
                            ? VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR
                            : static_cast<VkCompositeAlphaFlagBitsKHR>(caps.supportedCompositeAlpha & -caps.supportedCompositeAlpha);
  info.presentMode = mode;
  info.clipped = VK_TRUE;
  info.oldSwapchain = m_swapchain;
  VkSwapchainKHR created = VK_NULL_HANDLE;
  vk::check(vkCreateSwapchainKHR(device, &info, nullptr, &created), "vkCreateSwapchainKHR");
  destroy_swapchain();
  m_swapchain = created;
  vkGetSwapchainImagesKHR(device, m_swapchain, &n, nullptr);
  m_images.resize(n);
  vkGetSwapchainImagesKHR(device, m_swapchain, &n, m_images.data());
  if (m_direct || m_overlay_capable) {
    m_views.resize(n, VK_NULL_HANDLE);
    for (std::uint32_t i = 0; i < n; ++i) {
      VkImageViewCreateInfo view{};
      view.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
      view.image = m_images[i];
      view.viewType = VK_IMAGE_VIEW_TYPE_2D;
      view.format = m_format;
      view.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
      vk::check(vkCreateImageView(device, &view, nullptr, &m_views[i]), "vkCreateImageView");
    }
  }
  VkSemaphoreCreateInfo sem{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO, nullptr, 0};
  m_rendered.resize(n);
  for (VkSemaphore& s : m_rendered) vk::check(vkCreateSemaphore(device, &sem, nullptr, &s), "vkCreateSemaphore");
}

void Presenter::destroy_swapchain() {
  VkDevice device = m_context.device();
  for (VkSemaphore s : m_rendered) vkDestroySemaphore(device, s, nullptr);
  m_rendered.clear();
  for (VkImageView v : m_views) vkDestroyImageView(device, v, nullptr);
  m_views.clear();
  if (m_swapchain != VK_NULL_HANDLE) vkDestroySwapchainKHR(device, m_swapchain, nullptr);
  m_swapchain = VK_NULL_HANDLE;
  m_images.clear();
}

void Presenter::recreate(bool vsync) {
  VkDevice device = m_context.device();
  wait_for_frame();  // nothing in flight may use the old images (a resize, a path change: not per frame)
  vkDeviceWaitIdle(device);  // nor may a present
  // An acquire semaphore may be left signalled by an acquire whose frame was dropped: fresh ones.
  for (Slot& slot : m_slots) {
    vkDestroySemaphore(device, slot.acquired, nullptr);
    slot.acquired = VK_NULL_HANDLE;
    VkSemaphoreCreateInfo sem{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO, nullptr, 0};
    vk::check(vkCreateSemaphore(device, &sem, nullptr, &slot.acquired), "vkCreateSemaphore");
  }
  m_out_of_date = false;
  create_swapchain(vsync);
}

void Presenter::retire(Slot& slot) {
  vk::check(vkWaitForFences(m_context.device(), 1, &slot.done, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  // Targets that only frames up to this one could read.
  std::erase_if(m_retired_targets, [&](const auto& r) { return r.first <= slot.frame; });
  if (!slot.pending) return;
  slot.pending = false;
  const std::optional<vk::FrameTimer::Reading> t = slot.timer->read();
  if (!t) return;  // no device clock: nothing to count
  const std::optional<double> interval =
      slot.follows && m_last_end ? std::optional<double>(slot.timer->elapsed_ms(*m_last_end, t->end)) : std::nullopt;
  m_stats.add(interval, slot.timer->elapsed_ms(t->begin, t->end), slot.record_ms, slot.period_ms);
  m_last_end = t->end;
}

void Presenter::wait_for_frame() {
  // In frame order, so that the intervals are counted in turn.
  for (long k = 0; k < kFramesInFlight; ++k) retire(m_slots[(m_frames + k) % kFramesInFlight]);
}

std::optional<Presenter::Shown> Presenter::present(vk::MarchRenderer& renderer, std::span<const Camera> eyes,
                                                   int eye_width, int eye_height, const FrameOptions& options) {
  const bool capture = options.capture, vsync = options.vsync;
  const OverlayDraw* overlay = options.overlay;
  VkDevice device = m_context.device();
  const int render_w = eye_width * static_cast<int>(eyes.size()), render_h = eye_height;
  // The path: direct when the kernel renders at the window's size and the
  // surface allows it; a change of path re-creates the swapchain (UNORM
  // with STORAGE usage for the direct path, sRGB for the blit).
  auto fits_window = [&] {
    return static_cast<std::uint32_t>(render_w) == m_extent.width && static_cast<std::uint32_t>(render_h) == m_extent.height;
  };
  // Accumulating (or showing an accumulation) needs the float image: the blit path.
  const bool accumulating = options.sample.has_value() || options.reuse;
  m_prefer_direct = m_allow_direct && fits_window() && !accumulating;
  if (m_direct_capable && m_direct != m_prefer_direct) {
    recreate(vsync);
    if (!ready()) return std::nullopt;  // minimised meanwhile
  }
  if (m_direct && !fits_window()) {  // the window changed size meanwhile
    m_out_of_date = true;
    return std::nullopt;
  }
  const bool direct = m_direct;

  // Frames in flight: this frame's slot held frame n - kFramesInFlight,
  // which must be done before its command buffer and semaphore are reused
  // (with the swapchain's pacing it long is). The previous frame may still run.
  Slot& slot = m_slots[m_frames % kFramesInFlight];
  retire(slot);
  if (!direct && (!m_target || m_rendered_w != render_w || m_rendered_h != render_h)) {
    // The frames before this one may still read the old image: kept until they are done.
    if (m_target) m_retired_targets.emplace_back(m_frames - 1, std::move(*m_target));
    if (m_shown) m_retired_targets.emplace_back(m_frames - 1, std::move(*m_shown));
    m_target.reset();
    m_shown.reset();
    m_target.emplace(m_context, static_cast<std::uint32_t>(render_w), static_cast<std::uint32_t>(render_h));
    m_rendered_w = render_w;
    m_rendered_h = render_h;
    m_target_has_frame = false;
  }
  // Reuse only what the image holds at this size; else render (sample 0).
  const bool reuse = options.reuse && !direct && m_target_has_frame;
  std::uint32_t index = 0;
  const VkResult acquired = vkAcquireNextImageKHR(device, m_swapchain, UINT64_MAX, slot.acquired, VK_NULL_HANDLE, &index);
  if (acquired == VK_ERROR_OUT_OF_DATE_KHR) {
    m_out_of_date = true;
    return std::nullopt;
  }
  if (acquired != VK_SUBOPTIMAL_KHR) vk::check(acquired, "vkAcquireNextImageKHR");
  vk::check(vkResetFences(device, 1, &slot.done), "vkResetFences");

  const auto record_begin = std::chrono::steady_clock::now();
  VkCommandBuffer cb = slot.commands;
  vk::check(vkResetCommandBuffer(cb, 0), "vkResetCommandBuffer");
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO, nullptr,
                                 VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT, nullptr};
  vk::check(vkBeginCommandBuffer(cb, &begin), "vkBeginCommandBuffer");
  slot.timer->begin(cb);
  VkImage swap_image = m_images[index];
  // Where the swapchain image is once the frame is in it, and the last
  // stage and access that wrote it.
  VkImageLayout shown_layout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  VkPipelineStageFlags shown_stage = VK_PIPELINE_STAGE_TRANSFER_BIT;
  VkAccessFlags shown_access = VK_ACCESS_TRANSFER_WRITE_BIT;
  if (direct) {
    // The kernel writes the swapchain image itself: its old contents are
    // not needed (UNDEFINED) and storage writes need GENERAL. The
    // transition waits at the compute stage, the stage the submit's wait on
    // `acquired` blocks, so it happens only after the presentation engine
    // has released the image, and the kernel's writes come after it.
    vk::image_barrier(cb, swap_image, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                      VK_ACCESS_SHADER_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
    renderer.record(cb, eyes, eye_width, eye_height,
                    vk::UnormTarget{m_views[index], m_format, m_extent.width, m_extent.height, options.display});
    shown_layout = VK_IMAGE_LAYOUT_GENERAL;
    shown_stage = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
    shown_access = VK_ACCESS_SHADER_WRITE_BIT;
  } else {
    if (!reuse) renderer.record(cb, eyes, eye_width, eye_height, *m_target, options.sample.value_or(vk::PixelSample{}));
    record_blit(cb, swap_image, render_w, render_h, options.display, fits_window() || !m_linear_blit);
  }
  // The overlay, drawn into the image as a colour attachment; before the
  // capture when screenshots take it, else after.
  const bool drawing_overlay = overlay && overlay->record && m_overlay_capable;
  auto draw_overlay = [&] {
    vk::image_barrier(cb, swap_image, shown_stage, shown_access, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                      VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, shown_layout,
                      VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    overlay->record(cb, m_views[index], m_format, m_extent.width, m_extent.height);
    shown_layout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    shown_stage = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    shown_access = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  };
  if (drawing_overlay && overlay->in_capture) draw_overlay();
  // Screenshots and --record take the frame as shown: the swapchain image
  // after the blit, copied to a host-visible buffer.
  const bool capturing = m_can_capture && capture;
  if (capturing) {
    const VkDeviceSize bytes = VkDeviceSize{m_extent.width} * m_extent.height * 4;
    if (!m_capture || m_capture->size() != bytes) m_capture.emplace(m_context, bytes);
    // Read after write: the copy reads what the blit or the kernel wrote.
    vk::image_barrier(cb, swap_image, shown_stage, shown_access, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT,
                      shown_layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    VkBufferImageCopy copy{};
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.imageExtent = {m_extent.width, m_extent.height, 1};
    vkCmdCopyImageToBuffer(cb, swap_image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, m_capture->handle(), 1, &copy);
    // The host reads the buffer after the fence: make the copy's writes visible to it.
    VkBufferMemoryBarrier host{};
    host.sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER;
    host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    host.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    host.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    host.buffer = m_capture->handle();
    host.size = VK_WHOLE_SIZE;
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0, nullptr, 1, &host, 0, nullptr);
    shown_layout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    shown_stage = VK_PIPELINE_STAGE_TRANSFER_BIT;
    shown_access = VK_ACCESS_TRANSFER_READ_BIT;
  }
  if (drawing_overlay && !overlay->in_capture) draw_overlay();
  // To the presentation layout; the present waits on `rendered`, which the
  // submit signals after all these commands, so no later stage needs to wait here.
  vk::image_barrier(cb, swap_image, shown_stage, shown_access, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 0, shown_layout,
                    VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);
  slot.timer->end(cb);
  vk::check(vkEndCommandBuffer(cb), "vkEndCommandBuffer");
  const double record_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - record_begin).count();

  // The first use of the swapchain image waits for the acquire: the kernel
  // on the direct path; the blit otherwise (the kernel may run before the image is free).
  const VkPipelineStageFlags wait_stage = direct ? VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT : VK_PIPELINE_STAGE_TRANSFER_BIT;
  VkSubmitInfo submit{};
  submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
  submit.waitSemaphoreCount = 1;
  submit.pWaitSemaphores = &slot.acquired;
  submit.pWaitDstStageMask = &wait_stage;
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cb;
  submit.signalSemaphoreCount = 1;
  submit.pSignalSemaphores = &m_rendered[index];
  vk::check(vkQueueSubmit(m_context.queue(), 1, &submit, slot.done), "vkQueueSubmit");
  // Counted once done (retire): frames with the kernel; one shown again breaks the chain.
  slot.frame = m_frames++;
  slot.pending = !reuse;
  slot.follows = m_chain;
  slot.record_ms = record_ms;
  slot.period_ms = options.period_ms;
  m_chain = !reuse;
  VkPresentInfoKHR info{};
  info.sType = VK_STRUCTURE_TYPE_PRESENT_INFO_KHR;
  info.waitSemaphoreCount = 1;
  info.pWaitSemaphores = &m_rendered[index];
  info.swapchainCount = 1;
  info.pSwapchains = &m_swapchain;
  info.pImageIndices = &index;
  const VkResult presented = vkQueuePresentKHR(m_context.queue(), &info);
  if (presented == VK_ERROR_OUT_OF_DATE_KHR || presented == VK_SUBOPTIMAL_KHR) {
    m_out_of_date = true;
  } else {
    vk::check(presented, "vkQueuePresentKHR");
  }
  m_target_has_frame = !direct;
  m_display = options.display;
  if (capturing) {
    m_captured_w = m_extent.width;
    m_captured_h = m_extent.height;
    m_captured_format = m_format;
    m_captured_direct = direct;
  }
  return Shown{direct, record_ms, !reuse};
}

// The blit path's commands after the kernel: the display pass where the
// display is not the default, the blit into the swapchain image (nearest
// or linear filtering), and the barriers around them.
void Presenter::record_blit(VkCommandBuffer cb, VkImage swap_image, int render_w, int render_h, const Display& display,
                            bool nearest) {
  // A display other than the default: shown into m_shown by the display
  // pass (after the kernel's writes; the next frame's kernel writes the
  // target only after the pass has read it), and blitted from there.
  if (display != Display{}) {
    if (!m_display_pass) m_display_pass.emplace(m_context, static_cast<std::uint32_t>(kFramesInFlight));
    if (!m_shown) m_shown.emplace(m_context, m_target->width(), m_target->height());
    vk::record_memory_barrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                              VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
    m_display_pass->record(cb, *m_target, *m_shown, render_w, render_h, display,
                           static_cast<std::uint32_t>(m_frames % kFramesInFlight));
    vk::record_memory_barrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT,
                              VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT);
  }
  const VkImage target_image = display != Display{} ? m_shown->handle() : m_target->handle();
  // Read after write: the blit reads what the kernel (or the display pass)
  // wrote; to the layout blits read best (the previous frame's last
  // barrier already ordered this frame's writes after that frame's blit).
  vk::image_barrier(cb, target_image, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                    VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT, VK_IMAGE_LAYOUT_GENERAL,
                    VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  // The swapchain image: its old contents are not needed (UNDEFINED); the
  // transition waits at the transfer stage, the stage the submit's wait on
  // `acquired` blocks, so it happens only after the presentation engine
  // has released the image.
  vk::image_barrier(cb, swap_image, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT,
                    VK_ACCESS_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
  VkImageBlit blit{};
  blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  blit.srcOffsets[1] = {render_w, render_h, 1};
  blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  blit.dstOffsets[1] = {static_cast<std::int32_t>(m_extent.width), static_cast<std::int32_t>(m_extent.height), 1};
  vkCmdBlitImage(cb, target_image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, swap_image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                 1, &blit, nearest ? VK_FILTER_NEAREST : VK_FILTER_LINEAR);
  // Back to GENERAL, where Sol::vk expects its storage images between
  // commands (the next kernel, download()); write after read: the next
  // frame's kernel (which reads the image too when it accumulates) and any
  // download's copy wait for the blit to finish reading.
  vk::image_barrier(cb, target_image, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT,
                    VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                    VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_READ_BIT,
                    VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL);
}

void Presenter::save(const std::string& path) {
  // The frame's commands must be done before the host reads the capture or the target.
  wait_for_frame();
  if (m_captured_w != 0) {
    write_capture(path);
  } else if (m_target && m_target_has_frame) {
    write_rendered(path);
  } else {
    throw std::runtime_error(path + ": no frame was rendered");
  }
}

// The captured frame as 8-bit sRGB, like solrender's PNGs.
void Presenter::write_capture(const std::string& path) const {
  const std::uint32_t w = m_captured_w, h = m_captured_h;
  const auto* bytes = reinterpret_cast<const unsigned char*>(m_capture->bytes().data());
  const VkFormat format = m_captured_format;
  const bool bgr = format == VK_FORMAT_B8G8R8A8_SRGB || format == VK_FORMAT_B8G8R8A8_UNORM;
  const bool srgb = format == VK_FORMAT_B8G8R8A8_SRGB || format == VK_FORMAT_R8G8B8A8_SRGB || m_captured_direct;
  std::vector<float> rgba(std::size_t{w} * h * 4);
  for (std::size_t k = 0; k < std::size_t{w} * h; ++k) {
    for (std::size_t c = 0; c < 4; ++c) {
      const std::size_t from = bgr && c < 3 ? 2 - c : c;
      rgba[4 * k + c] = static_cast<float>(bytes[4 * k + from]) / 255.0f;
    }
  }
  // sRGB swapchain, or the direct path's UNORM one that the kernel wrote
  // sRGB-encoded: the bytes are already encoded (written as they are);
  // another UNORM one holds linear values, encoded on the way out.
  programs::write_image(path, static_cast<int>(w), static_cast<int>(h), {"R", "G", "B", "A"}, rgba, !srgb);
}

// The rendered image (before scaling) as 8-bit sRGB, through the frame's display.
void Presenter::write_rendered(const std::string& path) const {
  const std::vector<float> all = m_target->download();
  const int width = m_rendered_w, height = m_rendered_h;
  std::vector<float> rgba(static_cast<std::size_t>(width) * height * 4);
  for (int j = 0; j < height; ++j) {
    std::copy_n(all.begin() + static_cast<std::ptrdiff_t>(j) * m_target->width() * 4, width * 4,
                rgba.begin() + static_cast<std::ptrdiff_t>(j) * width * 4);
  }
  programs::write_image(path, width, height, {"R", "G", "B", "A"}, rgba, true, m_display);
}

}  // namespace sol::viewer
