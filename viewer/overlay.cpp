#include "overlay.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_vulkan.h>

#include <sol/vk/error.hpp>

#include "presenter.hpp"

namespace sol::viewer {
namespace {

void check_imgui_result(VkResult result) {
  if (result != VK_SUCCESS) throw std::runtime_error("ImGui's Vulkan backend: VkResult " + std::to_string(result));
}

bool is_srgb(VkFormat format) {
  return format == VK_FORMAT_B8G8R8A8_SRGB || format == VK_FORMAT_R8G8B8A8_SRGB || format == VK_FORMAT_A8B8G8R8_SRGB_PACK32;
}

// ImGui's colours are meant as they are stored (sRGB-encoded values). An
// sRGB swapchain encodes what is written, so there the style's colours are
// decoded first (the standard sRGB EOTF), and the panel looks the same on both paths.
void apply_style(bool srgb_target) {
  ImGuiStyle style;
  ImGui::StyleColorsDark(&style);
  style.WindowRounding = 0.0f;
  if (srgb_target) {
    auto decode = [](float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); };
    for (ImVec4& c : style.Colors) c = ImVec4(decode(c.x), decode(c.y), decode(c.z), c.w);
  }
  ImGui::GetStyle() = style;
}

}  // namespace

Overlay::Overlay(vk::Context& context, GLFWwindow* window) : m_context(context) {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // no imgui.ini beside the user's files: the panel starts where the viewer puts it
  io.LogFilename = nullptr;
  if (!ImGui_ImplGlfw_InitForVulkan(window, true)) {
    ImGui::DestroyContext();
    throw std::runtime_error("ImGui's GLFW backend failed to start");
  }
  // A pool for the backend's one descriptor set (the font texture).
  const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 4};
  VkDescriptorPoolCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO, nullptr,
                                  VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT, 4, 1, &size};
  const VkResult made = vkCreateDescriptorPool(context.device(), &info, nullptr, &m_pool);
  if (made != VK_SUCCESS) {
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    vk::check(made, "vkCreateDescriptorPool");
  }
}

Overlay::~Overlay() {
  vkDeviceWaitIdle(m_context.device());
  destroy_backend();
  for (VkFramebuffer f : m_framebuffers) {
    if (f) vkDestroyFramebuffer(m_context.device(), f, nullptr);
  }
  m_framebuffers.clear();
  vkDestroyDescriptorPool(m_context.device(), m_pool, nullptr);
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
}

void Overlay::destroy_backend() {
  if (m_backend) ImGui_ImplVulkan_Shutdown();
  m_backend = false;
  if (m_render_pass) vkDestroyRenderPass(m_context.device(), m_render_pass, nullptr);
  m_render_pass = VK_NULL_HANDLE;
  m_format = VK_FORMAT_UNDEFINED;
}

void Overlay::build_backend(VkFormat format) {
  VkDevice device = m_context.device();
  vkDeviceWaitIdle(device);  // the old pipeline and font texture may still be in use
  destroy_backend();
  // Over the frame already in the image: load it, keep it, and leave the
  // layout as it came (the presenter's barriers take it on).
  VkAttachmentDescription colour{};
  colour.format = format;
  colour.samples = VK_SAMPLE_COUNT_1_BIT;
  colour.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
  colour.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  colour.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  colour.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  colour.initialLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  colour.finalLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  VkAttachmentReference reference{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &reference;
  VkRenderPassCreateInfo pass{};
  pass.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO;
  pass.attachmentCount = 1;
  pass.pAttachments = &colour;
  pass.subpassCount = 1;
  pass.pSubpasses = &subpass;
  vk::check(vkCreateRenderPass(device, &pass, nullptr, &m_render_pass), "vkCreateRenderPass");

  ImGui_ImplVulkan_InitInfo init{};
  init.Instance = m_context.instance();
  init.PhysicalDevice = m_context.physical_device();
  init.Device = device;
  init.QueueFamily = m_context.queue_family_index();
  init.Queue = m_context.queue();
  init.DescriptorPool = m_pool;
  init.MinImageCount = 2;
  // Vertex buffers per frame, taken in turn: more than the presenter's
  // frames in flight, so that none is rewritten while a pending frame reads it.
  init.ImageCount = sol::viewer::kFramesInFlight + 1;
  init.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
  init.CheckVkResultFn = check_imgui_result;
  if (!ImGui_ImplVulkan_Init(&init, m_render_pass)) throw std::runtime_error("ImGui's Vulkan backend failed to start");
  m_backend = true;
  m_format = format;
  m_context.submit_and_wait([](VkCommandBuffer cb) { ImGui_ImplVulkan_CreateFontsTexture(cb); });
  ImGui_ImplVulkan_DestroyFontUploadObjects();
  apply_style(is_srgb(format));
}

void Overlay::begin_frame(VkFormat format) {
  if (!m_backend || format != m_format) build_backend(format);
  ImGui_ImplVulkan_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
}

void Overlay::end_frame() { ImGui::Render(); }

bool Overlay::wants_mouse() const { return ImGui::GetIO().WantCaptureMouse; }
bool Overlay::wants_keyboard() const { return ImGui::GetIO().WantCaptureKeyboard; }

void Overlay::record(VkCommandBuffer command_buffer, VkImageView view, VkFormat format, std::uint32_t width,
                     std::uint32_t height) {
  if (!m_backend || format != m_format) return;  // the draw lists belong to the other format's backend
  VkDevice device = m_context.device();
  m_framebuffers.resize(kFramesInFlight, VK_NULL_HANDLE);
  VkFramebuffer& framebuffer = m_framebuffers[m_next_framebuffer];
  m_next_framebuffer = (m_next_framebuffer + 1) % m_framebuffers.size();
  if (framebuffer) vkDestroyFramebuffer(device, framebuffer, nullptr);  // kFramesInFlight calls ago: its frame is done
  framebuffer = VK_NULL_HANDLE;
  VkFramebufferCreateInfo fb{};
  fb.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
  fb.renderPass = m_render_pass;
  fb.attachmentCount = 1;
  fb.pAttachments = &view;
  fb.width = width;
  fb.height = height;
  fb.layers = 1;
  vk::check(vkCreateFramebuffer(device, &fb, nullptr, &framebuffer), "vkCreateFramebuffer");
  VkRenderPassBeginInfo begin{};
  begin.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
  begin.renderPass = m_render_pass;
  begin.framebuffer = framebuffer;
  begin.renderArea = {{0, 0}, {width, height}};
  vkCmdBeginRenderPass(command_buffer, &begin, VK_SUBPASS_CONTENTS_INLINE);
  if (ImDrawData* draw = ImGui::GetDrawData()) ImGui_ImplVulkan_RenderDrawData(draw, command_buffer);
  vkCmdEndRenderPass(command_buffer);
}

}  // namespace sol::viewer
