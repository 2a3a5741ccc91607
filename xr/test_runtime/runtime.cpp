// A headless OpenXR runtime for testing solxr without a headset.
//
// Loaded by the real OpenXR loader through a manifest (XR_RUNTIME_JSON), it
// implements what solxr calls and nothing more: XR_KHR_vulkan_enable2 on the
// default Vulkan driver (lavapipe in the tests), one stereo HMD, swapchains
// of VkImages it owns, a frame loop that reads back every submitted eye image
// and saves it, head poses, controller thumbsticks and session events from a
// script, and a count of live objects (any the application did not destroy
// is reported as "LEAK" on stderr).
//
// The script is the JSON file named by SOLXR_TEST_SCRIPT (all keys optional):
//   {"mode": "normal" | "no_vulkan" | "no_hmd",
//    "width": 32, "height": 32,        recommended per-eye size
//    "fov": 60,                        vertical field of view, degrees (symmetric;
//                                      horizontal from width / height)
//    "fov_angles": [l, r, d, u],       instead: XrFovf angles in degrees (off-centre;
//                                      left and down negative), both eyes
//    "ipd": 0.064,                     metres
//    "formats": ["rgba32f", "srgb8"],  swapchain formats, runtime preference first
//    "controllers": true,              false: no interaction profile, inactive actions
//    "output": "DIR",                  where eye images go (none: not saved)
//    "image_format": "exr",            "exr" (linear float) or "png" (8-bit sRGB)
//    "read_back": true,                false: the timing mode: no eye image is read
//                                      back or saved (views.txt is still written)
//    "refresh_hz": 90,                 the display's rate: predictedDisplayPeriod (not paced)
//    "frames": [{"position": [x, y, z], "orientation": [x, y, z, w],  head pose
//                "left_stick": [x, y], "right_stick": [x, y],
//                "event": "focus_loss" | "focus_gain" | "exit" | "loss_pending"}, ...]}
// Frame k (counted by xrWaitFrame) uses entry min(k, last); events fire when
// frame k is waited for. After the last entry the runtime asks the
// application to exit (state STOPPING), so a script of N entries runs N frames.
// Saved images: DIR/frame<k>_view<v>.exr (or .png), RGBA, row 0 at the top,
// written as solrender writes its images (8-bit sRGB swapchains are decoded
// to linear first, so an EXR holds linear colour either way); DIR/views.txt
// gets a line per image:
// "k v px py pz qx qy qz qw angleLeft angleRight angleUp angleDown".
// docs/solxr.md documents the script and the files for users.
#include <vulkan/vulkan.h>

#include "image_file.hpp"  // Sol::programs: solrender's image writer

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>
#define XR_USE_GRAPHICS_API_VULKAN
#include <openxr/openxr.h>
#include <openxr/openxr_platform.h>
#include <openxr/openxr_reflection.h>

// The loader-runtime negotiation (OpenXR loader specification; Debian ships
// no loader_interfaces.h).
extern "C" {
enum XrLoaderInterfaceStructs {
  XR_LOADER_INTERFACE_STRUCT_UNINTIALIZED = 0,
  XR_LOADER_INTERFACE_STRUCT_LOADER_INFO,
  XR_LOADER_INTERFACE_STRUCT_API_LAYER_REQUEST,
  XR_LOADER_INTERFACE_STRUCT_RUNTIME_REQUEST,
};
struct XrNegotiateLoaderInfo {
  XrLoaderInterfaceStructs structType;
  uint32_t structVersion;
  size_t structSize;
  uint32_t minInterfaceVersion;
  uint32_t maxInterfaceVersion;
  XrVersion minApiVersion;
  XrVersion maxApiVersion;
};
struct XrNegotiateRuntimeRequest {
  XrLoaderInterfaceStructs structType;
  uint32_t structVersion;
  size_t structSize;
  uint32_t runtimeInterfaceVersion;
  XrVersion runtimeApiVersion;
  PFN_xrGetInstanceProcAddr getInstanceProcAddr;
};
__attribute__((visibility("default"))) XrResult xrNegotiateLoaderRuntimeInterface(
    const XrNegotiateLoaderInfo* loaderInfo, XrNegotiateRuntimeRequest* runtimeRequest);
}

namespace {

constexpr XrSystemId kSystem = 1;
// The display period, nanoseconds: the script's "refresh_hz" (default 90).
XrTime period();
constexpr std::uint32_t kImagesPerSwapchain = 3;

void say(const std::string& text) { std::fprintf(stderr, "sol test runtime: %s\n", text.c_str()); }

// ---------------------------------------------------------------------------
// The script.
struct Frame {
  double position[3] = {0, 0, 0};
  double orientation[4] = {0, 0, 0, 1};  // x, y, z, w
  float left_stick[2] = {0, 0}, right_stick[2] = {0, 0};
  std::string event;
};

struct Script {
  std::string mode = "normal";
  std::uint32_t width = 32, height = 32;
  double fov = 60.0, ipd = 0.064;
  std::vector<double> fov_angles;  // degrees: left, right, down, up (empty: symmetric from fov)
  std::vector<std::int64_t> formats{VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_R8G8B8A8_SRGB};
  bool controllers = true;
  std::string output;
  bool read_back = true;
  std::string image_format = "exr";
  double refresh_hz = 90.0;
  std::vector<Frame> frames{Frame{}};
};

Script load_script() {
  Script s;
  const char* path = std::getenv("SOLXR_TEST_SCRIPT");
  if (path == nullptr || *path == '\0') return s;
  std::ifstream in(path);
  if (!in) {
    say(std::string("cannot open SOLXR_TEST_SCRIPT ") + path);
    std::abort();
  }
  const nlohmann::json j = nlohmann::json::parse(in);
  s.mode = j.value("mode", s.mode);
  s.width = j.value("width", s.width);
  s.height = j.value("height", s.height);
  s.fov = j.value("fov", s.fov);
  if (j.contains("fov_angles")) s.fov_angles = j["fov_angles"].get<std::vector<double>>();
  s.ipd = j.value("ipd", s.ipd);
  s.controllers = j.value("controllers", s.controllers);
  s.output = j.value("output", s.output);
  s.read_back = j.value("read_back", s.read_back);
  if (!s.output.empty()) {
    std::error_code error;
    std::filesystem::create_directories(s.output, error);
    if (error) {
      say("SOLXR_TEST_SCRIPT: cannot make the output folder " + s.output + ": " + error.message());
      std::abort();
    }
  }
  s.image_format = j.value("image_format", s.image_format);
  if (s.image_format != "exr" && s.image_format != "png") {
    say("SOLXR_TEST_SCRIPT: image_format must be \"exr\" or \"png\", not \"" + s.image_format + "\"");
    std::abort();
  }
  s.refresh_hz = j.value("refresh_hz", s.refresh_hz);
  if (!(s.refresh_hz >= 1.0 && s.refresh_hz <= 1000.0)) s.refresh_hz = 90.0;
  if (j.contains("formats")) {
    s.formats.clear();
    for (const std::string f : j["formats"]) {
      s.formats.push_back(f == "srgb8" ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R32G32B32A32_SFLOAT);
    }
  }
  if (j.contains("frames")) {
    s.frames.clear();
    for (const auto& f : j["frames"]) {
      Frame frame;
      for (int i = 0; i < 3; ++i) frame.position[i] = f.value("position", std::vector<double>{0, 0, 0}).at(i);
      for (int i = 0; i < 4; ++i) frame.orientation[i] = f.value("orientation", std::vector<double>{0, 0, 0, 1}).at(i);
      for (int i = 0; i < 2; ++i) frame.left_stick[i] = f.value("left_stick", std::vector<float>{0, 0}).at(i);
      for (int i = 0; i < 2; ++i) frame.right_stick[i] = f.value("right_stick", std::vector<float>{0, 0}).at(i);
      frame.event = f.value("event", "");
      s.frames.push_back(frame);
    }
  }
  return s;
}

// ---------------------------------------------------------------------------
// Objects. Handles are small integers; `live` names every object not yet destroyed.
struct Swapchain {
  XrSession session = XR_NULL_HANDLE;
  VkFormat format = VK_FORMAT_UNDEFINED;
  std::uint32_t width = 0, height = 0;
  std::vector<VkImage> images;
  std::vector<VkDeviceMemory> memory;
  std::uint32_t next = 0;            // next image to acquire
  int acquired = -1, released = -1;  // last acquired / released image
};

struct Action {
  XrActionType type = XR_ACTION_TYPE_BOOLEAN_INPUT;
  std::string binding;  // "left" or "right": the thumbstick it is bound to
};

struct State {
  Script script;
  std::map<std::uint64_t, std::string> live;  // handle -> kind
  std::uint64_t next_handle = 1;
  XrInstance instance = XR_NULL_HANDLE;
  VkInstance vk_instance = VK_NULL_HANDLE;
  VkPhysicalDevice vk_physical = VK_NULL_HANDLE;
  std::map<std::string, XrPath> paths;
  // The session (one at a time).
  XrSession session = XR_NULL_HANDLE;
  XrSessionState session_state = XR_SESSION_STATE_UNKNOWN;
  // The last state the application has polled: input focus follows it, so
  // that a state change takes effect when the application learns of it.
  XrSessionState polled_state = XR_SESSION_STATE_UNKNOWN;
  bool running = false, exit_requested = false;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  std::uint32_t queue_family = 0;
  std::deque<XrEventDataBuffer> events;
  std::map<std::uint64_t, Swapchain> swapchains;
  std::map<std::uint64_t, Action> actions;
  std::uint64_t waited = 0, ended = 0, saved = 0;  // frames waited for / ended, images saved
  bool frame_begun = false;                         // between xrBeginFrame and xrEndFrame

  ~State() {
    // The loader unloads the runtime after xrDestroyInstance; whatever is
    // still alive now was never destroyed.
    for (const auto& [handle, kind] : live)
      say("LEAK: " + kind + " " + std::to_string(handle) + " was never destroyed");
  }
};

State& state() {
  static State s;
  return s;
}

XrTime period() { return static_cast<XrTime>(std::llround(1e9 / state().script.refresh_hz)); }

std::uint64_t make(const std::string& kind) {
  const std::uint64_t h = state().next_handle++;
  state().live[h] = kind;
  return h;
}

bool alive(std::uint64_t handle, const std::string& kind) {
  const auto it = state().live.find(handle);
  return it != state().live.end() && it->second == kind;
}

const Frame& frame_at(std::uint64_t k) {
  const auto& frames = state().script.frames;
  return frames[std::min<std::size_t>(k, frames.size() - 1)];
}

void push_state(XrSessionState s) {
  State& st = state();
  st.session_state = s;
  XrEventDataBuffer buffer{};
  auto* e = reinterpret_cast<XrEventDataSessionStateChanged*>(&buffer);
  e->type = XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED;
  e->session = st.session;
  e->state = s;
  e->time = static_cast<XrTime>(st.waited) * period();
  st.events.push_back(buffer);
}

// ---------------------------------------------------------------------------
// Vulkan helpers.
std::uint32_t memory_type(std::uint32_t bits, VkMemoryPropertyFlags flags) {
  VkPhysicalDeviceMemoryProperties props;
  vkGetPhysicalDeviceMemoryProperties(state().vk_physical, &props);
  for (std::uint32_t i = 0; i < props.memoryTypeCount; ++i) {
    if ((bits & (1u << i)) != 0 && (props.memoryTypes[i].propertyFlags & flags) == flags) return i;
  }
  say("no suitable Vulkan memory type");
  std::abort();
}

void vk_check(VkResult r, const char* call) {
  if (r != VK_SUCCESS) {
    say(std::string(call) + " failed: " + std::to_string(r));
    std::abort();
  }
}

float srgb_to_linear(std::uint8_t byte) {
  const float c = static_cast<float>(byte) / 255.0f;
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

/// Copies the image to host memory (it is in COLOR_ATTACHMENT_OPTIMAL, as an
/// application releases it) and writes it as linear float RGBA.
void save_image(const Swapchain& sc, VkImage image, const std::string& path) {
  State& st = state();
  const std::size_t texel = sc.format == VK_FORMAT_R32G32B32A32_SFLOAT ? 16 : 4;
  const VkDeviceSize size = static_cast<VkDeviceSize>(sc.width) * sc.height * texel;
  VkBufferCreateInfo bi{};
  bi.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  bi.size = size;
  bi.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  VkBuffer buffer;
  if (vkCreateBuffer(st.device, &bi, nullptr, &buffer) != VK_SUCCESS) {
    say("cannot save " + path + ": no buffer of " + std::to_string(size) + " bytes");  // (the frame goes on)
    return;
  }
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(st.device, buffer, &req);
  VkMemoryAllocateInfo ai{};
  ai.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
  ai.allocationSize = req.size;
  ai.memoryTypeIndex =
      memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  VkDeviceMemory memory;
  if (vkAllocateMemory(st.device, &ai, nullptr, &memory) != VK_SUCCESS) {
    say("cannot save " + path + ": out of memory for " + std::to_string(size) + " bytes");
    vkDestroyBuffer(st.device, buffer, nullptr);
    return;
  }
  vk_check(vkBindBufferMemory(st.device, buffer, memory, 0), "vkBindBufferMemory");

  VkCommandPoolCreateInfo pi{};
  pi.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
  pi.queueFamilyIndex = st.queue_family;
  VkCommandPool pool;
  vk_check(vkCreateCommandPool(st.device, &pi, nullptr, &pool), "vkCreateCommandPool");
  VkCommandBufferAllocateInfo cai{};
  cai.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
  cai.commandPool = pool;
  cai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  cai.commandBufferCount = 1;
  VkCommandBuffer cmd;
  vk_check(vkAllocateCommandBuffers(st.device, &cai, &cmd), "vkAllocateCommandBuffers");
  VkCommandBufferBeginInfo begin{};
  begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  vk_check(vkBeginCommandBuffer(cmd, &begin), "vkBeginCommandBuffer");
  // The application's writes (any stage) before our copy; then back to the
  // layout the application expects at its next acquire.
  VkImageMemoryBarrier barrier{};
  barrier.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
  barrier.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
  barrier.oldLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  barrier.newLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.image = image;
  barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0,
                       nullptr, 1, &barrier);
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {sc.width, sc.height, 1};
  vkCmdCopyImageToBuffer(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer, 1, &region);
  barrier.srcAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
  barrier.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  barrier.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  barrier.newLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  VkBufferMemoryBarrier host{};
  host.sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER;
  host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  host.srcQueueFamilyIndex = host.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  host.buffer = buffer;
  host.size = VK_WHOLE_SIZE;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_PIPELINE_STAGE_HOST_BIT | VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, 0, 0, nullptr, 1,
                       &host, 1, &barrier);
  vk_check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
  VkSubmitInfo submit{};
  submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd;
  vk_check(vkQueueSubmit(st.queue, 1, &submit, VK_NULL_HANDLE), "vkQueueSubmit");
  vk_check(vkQueueWaitIdle(st.queue), "vkQueueWaitIdle");

  void* mapped = nullptr;
  vk_check(vkMapMemory(st.device, memory, 0, size, 0, &mapped), "vkMapMemory");
  const std::size_t n = static_cast<std::size_t>(sc.width) * sc.height * 4;
  std::vector<float> rgba(n);
  if (texel == 16) {
    std::memcpy(rgba.data(), mapped, n * sizeof(float));
  } else {
    const auto* bytes = static_cast<const std::uint8_t*>(mapped);
    for (std::size_t i = 0; i < n; ++i) {
      rgba[i] = (i % 4 == 3) ? static_cast<float>(bytes[i]) / 255.0f : srgb_to_linear(bytes[i]);
    }
  }
  vkUnmapMemory(st.device, memory);
  vkDestroyCommandPool(st.device, pool, nullptr);
  vkDestroyBuffer(st.device, buffer, nullptr);
  vkFreeMemory(st.device, memory, nullptr);

  try {
    sol::programs::write_image(path, static_cast<int>(sc.width), static_cast<int>(sc.height), {"R", "G", "B", "A"}, rgba, true);
  } catch (const std::exception& e) {
    say("cannot write " + path + ": " + e.what());
    std::abort();
  }
  ++st.saved;
}

void destroy_swapchain_images(Swapchain& sc) {
  for (VkImage image : sc.images) vkDestroyImage(state().device, image, nullptr);
  for (VkDeviceMemory memory : sc.memory) vkFreeMemory(state().device, memory, nullptr);
  sc.images.clear();
  sc.memory.clear();
}

// ---------------------------------------------------------------------------
// The OpenXR functions.
template <class T>
XrResult two_call(std::uint32_t capacity, std::uint32_t* count, T* out, const std::vector<T>& items) {
  if (count == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  *count = static_cast<std::uint32_t>(items.size());
  if (capacity == 0) return XR_SUCCESS;
  if (capacity < items.size()) return XR_ERROR_SIZE_INSUFFICIENT;
  std::copy(items.begin(), items.end(), out);
  return XR_SUCCESS;
}

std::vector<std::string> extension_names() {
  std::vector<std::string> names;
  if (state().script.mode != "no_vulkan") names.push_back(XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME);
  return names;
}

XRAPI_ATTR XrResult XRAPI_CALL EnumerateInstanceExtensionProperties(const char* layer, std::uint32_t capacity,
                                                                    std::uint32_t* count,
                                                                    XrExtensionProperties* props) {
  if (layer != nullptr) return XR_ERROR_API_LAYER_NOT_PRESENT;
  std::vector<XrExtensionProperties> items;
  for (const std::string& name : extension_names()) {
    XrExtensionProperties p{};
    p.type = XR_TYPE_EXTENSION_PROPERTIES;
    std::snprintf(p.extensionName, sizeof p.extensionName, "%s", name.c_str());
    p.extensionVersion = 1;
    items.push_back(p);
  }
  return two_call(capacity, count, props, items);
}

XRAPI_ATTR XrResult XRAPI_CALL CreateInstance(const XrInstanceCreateInfo* info, XrInstance* instance) {
  State& st = state();
  const auto names = extension_names();
  for (std::uint32_t i = 0; i < info->enabledExtensionCount; ++i) {
    if (std::find(names.begin(), names.end(), info->enabledExtensionNames[i]) == names.end()) {
      return XR_ERROR_EXTENSION_NOT_PRESENT;
    }
  }
  if (st.instance != XR_NULL_HANDLE) return XR_ERROR_LIMIT_REACHED;
  st.instance = reinterpret_cast<XrInstance>(make("XrInstance"));
  *instance = st.instance;
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL DestroyInstance(XrInstance instance) {
  State& st = state();
  if (instance != st.instance || instance == XR_NULL_HANDLE) return XR_ERROR_HANDLE_INVALID;
  st.live.erase(reinterpret_cast<std::uint64_t>(instance));
  for (const auto& [handle, kind] : st.live) say("LEAK: " + kind + " " + std::to_string(handle) + " was not destroyed");
  if (st.session != XR_NULL_HANDLE) {
    for (auto& [h, sc] : st.swapchains) destroy_swapchain_images(sc);
  }
  say(std::to_string(st.ended) + " frames ended, " + std::to_string(st.saved) + " images saved, " +
      std::to_string(st.live.size()) + " objects leaked");
  st.live.clear();
  st.swapchains.clear();
  st.actions.clear();
  st.instance = XR_NULL_HANDLE;
  st.session = XR_NULL_HANDLE;
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL GetInstanceProperties(XrInstance, XrInstanceProperties* props) {
  props->runtimeVersion = XR_MAKE_VERSION(0, 1, 0);
  std::snprintf(props->runtimeName, sizeof props->runtimeName, "Sol headless test runtime");
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL ResultToString(XrInstance, XrResult value, char buffer[XR_MAX_RESULT_STRING_SIZE]) {
#define SOL_RESULT_CASE(name, val)                                 \
  case name:                                                       \
    std::snprintf(buffer, XR_MAX_RESULT_STRING_SIZE, "%s", #name); \
    return XR_SUCCESS;
  switch (value) { XR_LIST_ENUM_XrResult(SOL_RESULT_CASE) default : break; }
#undef SOL_RESULT_CASE
  std::snprintf(buffer, XR_MAX_RESULT_STRING_SIZE, "XR_UNKNOWN_RESULT_%d", static_cast<int>(value));
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL GetSystem(XrInstance, const XrSystemGetInfo* info, XrSystemId* system) {
  if (state().script.mode == "no_hmd" || info->formFactor != XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY) {
    return XR_ERROR_FORM_FACTOR_UNAVAILABLE;
  }
  *system = kSystem;
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL GetSystemProperties(XrInstance, XrSystemId, XrSystemProperties* props) {
  props->systemId = kSystem;
  std::snprintf(props->systemName, sizeof props->systemName, "Sol headless HMD");
  props->graphicsProperties.maxSwapchainImageWidth = 16384;
  props->graphicsProperties.maxSwapchainImageHeight = 16384;
  props->graphicsProperties.maxLayerCount = 16;
  props->trackingProperties.orientationTracking = XR_TRUE;
  props->trackingProperties.positionTracking = XR_TRUE;
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL GetVulkanGraphicsRequirements2KHR(XrInstance, XrSystemId,
                                                                 XrGraphicsRequirementsVulkanKHR* req) {
  req->minApiVersionSupported = XR_MAKE_VERSION(1, 0, 0);
  req->maxApiVersionSupported = XR_MAKE_VERSION(1, 3, 0);
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL CreateVulkanInstanceKHR(XrInstance, const XrVulkanInstanceCreateInfoKHR* info,
                                                       VkInstance* instance, VkResult* result) {
  auto create =
      reinterpret_cast<PFN_vkCreateInstance>(info->pfnGetInstanceProcAddr(VK_NULL_HANDLE, "vkCreateInstance"));
  *result = create(info->vulkanCreateInfo, info->vulkanAllocator, instance);
  if (*result == VK_SUCCESS) state().vk_instance = *instance;
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL GetVulkanGraphicsDevice2KHR(XrInstance, const XrVulkanGraphicsDeviceGetInfoKHR* info,
                                                           VkPhysicalDevice* device) {
  std::uint32_t count = 0;
  vkEnumeratePhysicalDevices(info->vulkanInstance, &count, nullptr);
  std::vector<VkPhysicalDevice> devices(count);
  vkEnumeratePhysicalDevices(info->vulkanInstance, &count, devices.data());
  if (devices.empty()) return XR_ERROR_RUNTIME_FAILURE;
  *device = devices.front();
  state().vk_physical = *device;
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL CreateVulkanDeviceKHR(XrInstance, const XrVulkanDeviceCreateInfoKHR* info,
                                                     VkDevice* device, VkResult* result) {
  if (info->vulkanPhysicalDevice != state().vk_physical) return XR_ERROR_VALIDATION_FAILURE;
  *result = vkCreateDevice(info->vulkanPhysicalDevice, info->vulkanCreateInfo, info->vulkanAllocator, device);
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL EnumerateViewConfigurations(XrInstance, XrSystemId, std::uint32_t capacity,
                                                           std::uint32_t* count, XrViewConfigurationType* types) {
  return two_call(capacity, count, types,
                  std::vector<XrViewConfigurationType>{XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO});
}

XRAPI_ATTR XrResult XRAPI_CALL EnumerateViewConfigurationViews(XrInstance, XrSystemId, XrViewConfigurationType type,
                                                               std::uint32_t capacity, std::uint32_t* count,
                                                               XrViewConfigurationView* views) {
  if (type != XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO) return XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED;
  XrViewConfigurationView v{};
  v.type = XR_TYPE_VIEW_CONFIGURATION_VIEW;
  v.recommendedImageRectWidth = state().script.width;
  v.recommendedImageRectHeight = state().script.height;
  v.maxImageRectWidth = v.maxImageRectHeight = 16384;
  v.recommendedSwapchainSampleCount = v.maxSwapchainSampleCount = 1;
  return two_call(capacity, count, views, std::vector<XrViewConfigurationView>{v, v});
}

XRAPI_ATTR XrResult XRAPI_CALL EnumerateEnvironmentBlendModes(XrInstance, XrSystemId, XrViewConfigurationType,
                                                              std::uint32_t capacity, std::uint32_t* count,
                                                              XrEnvironmentBlendMode* modes) {
  return two_call(capacity, count, modes, std::vector<XrEnvironmentBlendMode>{XR_ENVIRONMENT_BLEND_MODE_OPAQUE});
}

XRAPI_ATTR XrResult XRAPI_CALL CreateSession(XrInstance, const XrSessionCreateInfo* info, XrSession* session) {
  State& st = state();
  if (st.session != XR_NULL_HANDLE) return XR_ERROR_LIMIT_REACHED;
  const auto* binding = static_cast<const XrGraphicsBindingVulkanKHR*>(info->next);
  if (binding == nullptr || binding->type != XR_TYPE_GRAPHICS_BINDING_VULKAN_KHR)
    return XR_ERROR_GRAPHICS_DEVICE_INVALID;
  if (binding->physicalDevice != st.vk_physical) return XR_ERROR_GRAPHICS_DEVICE_INVALID;
  st.device = binding->device;
  st.queue_family = binding->queueFamilyIndex;
  vkGetDeviceQueue(st.device, binding->queueFamilyIndex, binding->queueIndex, &st.queue);
  st.session = reinterpret_cast<XrSession>(make("XrSession"));
  st.running = st.exit_requested = false;
  st.waited = st.ended = 0;
  st.frame_begun = false;
  *session = st.session;
  push_state(XR_SESSION_STATE_IDLE);
  push_state(XR_SESSION_STATE_READY);
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL DestroySession(XrSession session) {
  State& st = state();
  if (session != st.session || session == XR_NULL_HANDLE) return XR_ERROR_HANDLE_INVALID;
  // Children the application forgot: reported as leaks by DestroyInstance.
  for (auto& [h, sc] : st.swapchains) destroy_swapchain_images(sc);
  st.live.erase(reinterpret_cast<std::uint64_t>(session));
  st.session = XR_NULL_HANDLE;
  st.running = false;
  st.events.clear();
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL BeginSession(XrSession session, const XrSessionBeginInfo* info) {
  State& st = state();
  if (session != st.session) return XR_ERROR_HANDLE_INVALID;
  if (st.running) return XR_ERROR_SESSION_RUNNING;
  if (st.session_state != XR_SESSION_STATE_READY) return XR_ERROR_SESSION_NOT_READY;
  if (info->primaryViewConfigurationType != XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO) {
    return XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED;
  }
  st.running = true;
  push_state(XR_SESSION_STATE_SYNCHRONIZED);
  push_state(XR_SESSION_STATE_VISIBLE);
  push_state(XR_SESSION_STATE_FOCUSED);
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL EndSession(XrSession session) {
  State& st = state();
  if (session != st.session) return XR_ERROR_HANDLE_INVALID;
  if (!st.running) return XR_ERROR_SESSION_NOT_RUNNING;
  if (st.session_state != XR_SESSION_STATE_STOPPING) return XR_ERROR_SESSION_NOT_STOPPING;
  st.running = false;
  push_state(XR_SESSION_STATE_IDLE);
  if (st.exit_requested) push_state(XR_SESSION_STATE_EXITING);
  return XR_SUCCESS;
}

void request_exit() {
  State& st = state();
  if (st.exit_requested) return;
  st.exit_requested = true;
  if (st.session_state == XR_SESSION_STATE_FOCUSED) push_state(XR_SESSION_STATE_VISIBLE);
  if (st.session_state == XR_SESSION_STATE_VISIBLE) push_state(XR_SESSION_STATE_SYNCHRONIZED);
  push_state(XR_SESSION_STATE_STOPPING);
}

XRAPI_ATTR XrResult XRAPI_CALL RequestExitSession(XrSession session) {
  if (session != state().session) return XR_ERROR_HANDLE_INVALID;
  if (!state().running) return XR_ERROR_SESSION_NOT_RUNNING;
  request_exit();
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL PollEvent(XrInstance, XrEventDataBuffer* event) {
  State& st = state();
  if (st.events.empty()) return XR_EVENT_UNAVAILABLE;
  *event = st.events.front();
  st.events.pop_front();
  if (event->type == XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED) {
    st.polled_state = reinterpret_cast<const XrEventDataSessionStateChanged*>(event)->state;
  }
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL EnumerateReferenceSpaces(XrSession, std::uint32_t capacity, std::uint32_t* count,
                                                        XrReferenceSpaceType* types) {
  return two_call(capacity, count, types,
                  std::vector<XrReferenceSpaceType>{XR_REFERENCE_SPACE_TYPE_LOCAL, XR_REFERENCE_SPACE_TYPE_STAGE,
                                                    XR_REFERENCE_SPACE_TYPE_VIEW});
}

XRAPI_ATTR XrResult XRAPI_CALL CreateReferenceSpace(XrSession session, const XrReferenceSpaceCreateInfo*,
                                                    XrSpace* space) {
  if (session != state().session) return XR_ERROR_HANDLE_INVALID;
  *space = reinterpret_cast<XrSpace>(make("XrSpace"));
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL DestroySpace(XrSpace space) {
  if (!alive(reinterpret_cast<std::uint64_t>(space), "XrSpace")) return XR_ERROR_HANDLE_INVALID;
  state().live.erase(reinterpret_cast<std::uint64_t>(space));
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL EnumerateSwapchainFormats(XrSession, std::uint32_t capacity, std::uint32_t* count,
                                                         std::int64_t* formats) {
  return two_call(capacity, count, formats, state().script.formats);
}

XRAPI_ATTR XrResult XRAPI_CALL CreateSwapchain(XrSession session, const XrSwapchainCreateInfo* info, XrSwapchain* out) {
  State& st = state();
  if (session != st.session) return XR_ERROR_HANDLE_INVALID;
  const auto& formats = st.script.formats;
  if (std::find(formats.begin(), formats.end(), info->format) == formats.end())
    return XR_ERROR_SWAPCHAIN_FORMAT_UNSUPPORTED;
  Swapchain sc;
  sc.session = session;
  sc.format = static_cast<VkFormat>(info->format);
  sc.width = info->width;
  sc.height = info->height;
  VkImageUsageFlags usage = VK_IMAGE_USAGE_TRANSFER_SRC_BIT;  // for our read-back
  if (info->usageFlags & XR_SWAPCHAIN_USAGE_COLOR_ATTACHMENT_BIT) usage |= VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
  if (info->usageFlags & XR_SWAPCHAIN_USAGE_TRANSFER_DST_BIT) usage |= VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  if (info->usageFlags & XR_SWAPCHAIN_USAGE_SAMPLED_BIT) usage |= VK_IMAGE_USAGE_SAMPLED_BIT;
  if (info->usageFlags & XR_SWAPCHAIN_USAGE_UNORDERED_ACCESS_BIT) usage |= VK_IMAGE_USAGE_STORAGE_BIT;
  for (std::uint32_t i = 0; i < kImagesPerSwapchain; ++i) {
    VkImageCreateInfo ii{};
    ii.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
    ii.imageType = VK_IMAGE_TYPE_2D;
    ii.format = sc.format;
    ii.extent = {sc.width, sc.height, 1};
    ii.mipLevels = 1;
    ii.arrayLayers = 1;
    ii.samples = VK_SAMPLE_COUNT_1_BIT;
    ii.tiling = VK_IMAGE_TILING_OPTIMAL;
    ii.usage = usage;
    ii.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkImage image = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    // An image the device cannot make or hold (a 16384² RGBA32F eye is 4
    // GiB): the call fails as a runtime's does, out of memory, not the process.
    bool made = vkCreateImage(st.device, &ii, nullptr, &image) == VK_SUCCESS;
    if (made) {
      VkMemoryRequirements req;
      vkGetImageMemoryRequirements(st.device, image, &req);
      VkMemoryAllocateInfo ai{};
      ai.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
      ai.allocationSize = req.size;
      ai.memoryTypeIndex = memory_type(req.memoryTypeBits, 0);
      made = vkAllocateMemory(st.device, &ai, nullptr, &memory) == VK_SUCCESS &&
             vkBindImageMemory(st.device, image, memory, 0) == VK_SUCCESS;
    }
    if (!made) {
      say("xrCreateSwapchain: cannot make a " + std::to_string(sc.width) + " x " + std::to_string(sc.height) +
          " image: out of memory");
      if (memory != VK_NULL_HANDLE) vkFreeMemory(st.device, memory, nullptr);
      if (image != VK_NULL_HANDLE) vkDestroyImage(st.device, image, nullptr);
      destroy_swapchain_images(sc);
      return XR_ERROR_OUT_OF_MEMORY;
    }
    sc.images.push_back(image);
    sc.memory.push_back(memory);
  }
  const std::uint64_t h = make("XrSwapchain");
  st.swapchains[h] = std::move(sc);
  *out = reinterpret_cast<XrSwapchain>(h);
  return XR_SUCCESS;
}

Swapchain* find_swapchain(XrSwapchain handle) {
  const auto it = state().swapchains.find(reinterpret_cast<std::uint64_t>(handle));
  return it == state().swapchains.end() ? nullptr : &it->second;
}

XRAPI_ATTR XrResult XRAPI_CALL DestroySwapchain(XrSwapchain swapchain) {
  Swapchain* sc = find_swapchain(swapchain);
  if (sc == nullptr) return XR_ERROR_HANDLE_INVALID;
  destroy_swapchain_images(*sc);
  state().swapchains.erase(reinterpret_cast<std::uint64_t>(swapchain));
  state().live.erase(reinterpret_cast<std::uint64_t>(swapchain));
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL EnumerateSwapchainImages(XrSwapchain swapchain, std::uint32_t capacity,
                                                        std::uint32_t* count, XrSwapchainImageBaseHeader* images) {
  Swapchain* sc = find_swapchain(swapchain);
  if (sc == nullptr) return XR_ERROR_HANDLE_INVALID;
  *count = static_cast<std::uint32_t>(sc->images.size());
  if (capacity == 0) return XR_SUCCESS;
  if (capacity < sc->images.size()) return XR_ERROR_SIZE_INSUFFICIENT;
  auto* vk_images = reinterpret_cast<XrSwapchainImageVulkanKHR*>(images);
  for (std::size_t i = 0; i < sc->images.size(); ++i) {
    if (vk_images[i].type != XR_TYPE_SWAPCHAIN_IMAGE_VULKAN_KHR) return XR_ERROR_VALIDATION_FAILURE;
    vk_images[i].image = sc->images[i];
  }
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL AcquireSwapchainImage(XrSwapchain swapchain, const XrSwapchainImageAcquireInfo*,
                                                     std::uint32_t* index) {
  Swapchain* sc = find_swapchain(swapchain);
  if (sc == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (sc->acquired >= 0) return XR_ERROR_CALL_ORDER_INVALID;  // one at a time is all solxr needs
  sc->acquired = static_cast<int>(sc->next);
  *index = sc->next;
  sc->next = (sc->next + 1) % kImagesPerSwapchain;
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL WaitSwapchainImage(XrSwapchain swapchain, const XrSwapchainImageWaitInfo*) {
  Swapchain* sc = find_swapchain(swapchain);
  if (sc == nullptr) return XR_ERROR_HANDLE_INVALID;
  return sc->acquired >= 0 ? XR_SUCCESS : XR_ERROR_CALL_ORDER_INVALID;
}

XRAPI_ATTR XrResult XRAPI_CALL ReleaseSwapchainImage(XrSwapchain swapchain, const XrSwapchainImageReleaseInfo*) {
  Swapchain* sc = find_swapchain(swapchain);
  if (sc == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (sc->acquired < 0) return XR_ERROR_CALL_ORDER_INVALID;
  sc->released = sc->acquired;
  sc->acquired = -1;
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL WaitFrame(XrSession session, const XrFrameWaitInfo*, XrFrameState* frame) {
  State& st = state();
  if (session != st.session) return XR_ERROR_HANDLE_INVALID;
  if (!st.running) return XR_ERROR_SESSION_NOT_RUNNING;
  const std::uint64_t k = st.waited++;
  frame->predictedDisplayTime = static_cast<XrTime>(k + 1) * period();
  frame->predictedDisplayPeriod = period();
  frame->shouldRender = st.session_state == XR_SESSION_STATE_VISIBLE || st.session_state == XR_SESSION_STATE_FOCUSED;
  // Scripted events for this frame, seen by the application's next poll.
  if (k < st.script.frames.size()) {
    const std::string& e = st.script.frames[k].event;
    if (e == "focus_loss" && st.session_state == XR_SESSION_STATE_FOCUSED) push_state(XR_SESSION_STATE_VISIBLE);
    if (e == "focus_gain" && st.session_state == XR_SESSION_STATE_VISIBLE) push_state(XR_SESSION_STATE_FOCUSED);
    if (e == "exit") request_exit();
    if (e == "loss_pending") push_state(XR_SESSION_STATE_LOSS_PENDING);
  }
  if (k + 1 >= st.script.frames.size()) request_exit();
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL BeginFrame(XrSession session, const XrFrameBeginInfo*) {
  State& st = state();
  if (session != st.session) return XR_ERROR_HANDLE_INVALID;
  if (!st.running) return XR_ERROR_SESSION_NOT_RUNNING;
  // solxr waits, begins and ends each frame in turn: anything else is a bug.
  if (st.frame_begun || st.waited != st.ended + 1) {
    say("xrBeginFrame out of order");
    return XR_ERROR_CALL_ORDER_INVALID;
  }
  st.frame_begun = true;
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL EndFrame(XrSession session, const XrFrameEndInfo* info) {
  State& st = state();
  if (session != st.session) return XR_ERROR_HANDLE_INVALID;
  if (!st.running) return XR_ERROR_SESSION_NOT_RUNNING;
  if (!st.frame_begun) {
    say("xrEndFrame without xrBeginFrame");
    return XR_ERROR_CALL_ORDER_INVALID;
  }
  st.frame_begun = false;
  const std::uint64_t k = static_cast<std::uint64_t>(info->displayTime / period()) - 1;
  if (info->displayTime != static_cast<XrTime>(st.waited) * period()) {
    say("xrEndFrame: displayTime is not the predicted one");
    return XR_ERROR_TIME_INVALID;
  }
  for (std::uint32_t l = 0; l < info->layerCount; ++l) {
    if (info->layers[l]->type != XR_TYPE_COMPOSITION_LAYER_PROJECTION) return XR_ERROR_LAYER_INVALID;
    const auto* layer = reinterpret_cast<const XrCompositionLayerProjection*>(info->layers[l]);
    if (layer->viewCount != 2) return XR_ERROR_VALIDATION_FAILURE;
    for (std::uint32_t v = 0; v < layer->viewCount; ++v) {
      const XrCompositionLayerProjectionView& view = layer->views[v];
      Swapchain* sc = find_swapchain(view.subImage.swapchain);
      if (sc == nullptr) return XR_ERROR_HANDLE_INVALID;
      if (sc->released < 0 || sc->acquired >= 0) {
        say("xrEndFrame: a view's swapchain has no released image, or one still acquired");
        return XR_ERROR_LAYER_INVALID;
      }
      const XrRect2Di& rect = view.subImage.imageRect;
      if (rect.offset.x < 0 || rect.offset.y < 0 || rect.extent.width <= 0 || rect.extent.height <= 0 ||
          static_cast<std::uint32_t>(rect.offset.x + rect.extent.width) > sc->width ||
          static_cast<std::uint32_t>(rect.offset.y + rect.extent.height) > sc->height) {
        say("xrEndFrame: imageRect outside the swapchain image");
        return XR_ERROR_SWAPCHAIN_RECT_INVALID;
      }
      if (st.script.output.empty()) continue;
      const std::string stem = st.script.output + "/frame" + std::to_string(k) + "_view" + std::to_string(v);
      if (st.script.read_back) save_image(*sc, sc->images[static_cast<std::size_t>(sc->released)], stem + "." + st.script.image_format);
      std::FILE* f = std::fopen((st.script.output + "/views.txt").c_str(), "a");
      if (f != nullptr) {
        const XrPosef& p = view.pose;
        std::fprintf(f, "%llu %u %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.9g %.9g %.9g %.9g\n",
                     static_cast<unsigned long long>(k), v, p.position.x, p.position.y, p.position.z, p.orientation.x,
                     p.orientation.y, p.orientation.z, p.orientation.w, view.fov.angleLeft, view.fov.angleRight,
                     view.fov.angleUp, view.fov.angleDown);
        std::fclose(f);
      }
    }
  }
  ++st.ended;
  return XR_SUCCESS;
}

/// Rotates v by the unit quaternion q = (x, y, z, w).
void rotate(const double q[4], const double v[3], double out[3]) {
  // v + 2w (u × v) + 2 u × (u × v), u = (x, y, z)
  const double u[3] = {q[0], q[1], q[2]}, w = q[3];
  const double c[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  const double cc[3] = {u[1] * c[2] - u[2] * c[1], u[2] * c[0] - u[0] * c[2], u[0] * c[1] - u[1] * c[0]};
  for (int i = 0; i < 3; ++i) out[i] = v[i] + 2.0 * w * c[i] + 2.0 * cc[i];
}

XRAPI_ATTR XrResult XRAPI_CALL LocateViews(XrSession session, const XrViewLocateInfo* info, XrViewState* view_state,
                                           std::uint32_t capacity, std::uint32_t* count, XrView* views) {
  State& st = state();
  if (session != st.session) return XR_ERROR_HANDLE_INVALID;
  *count = 2;
  if (capacity == 0) return XR_SUCCESS;
  if (capacity < 2) return XR_ERROR_SIZE_INSUFFICIENT;
  const std::uint64_t k = static_cast<std::uint64_t>(std::max<XrTime>(info->displayTime / period() - 1, 0));
  const Frame& f = frame_at(k);
  view_state->viewStateFlags = XR_VIEW_STATE_ORIENTATION_VALID_BIT | XR_VIEW_STATE_POSITION_VALID_BIT |
                               XR_VIEW_STATE_ORIENTATION_TRACKED_BIT | XR_VIEW_STATE_POSITION_TRACKED_BIT;
  const double half = 0.5 * st.script.fov * M_PI / 180.0;
  const double horizontal = std::atan(std::tan(half) * st.script.width / st.script.height);
  for (int v = 0; v < 2; ++v) {
    // Each eye sits ∓ipd/2 along the head's x axis (OpenXR: +x right).
    const double offset[3] = {(v == 0 ? -0.5 : 0.5) * st.script.ipd, 0.0, 0.0};
    double rotated[3];
    rotate(f.orientation, offset, rotated);
    views[v].pose.position = {static_cast<float>(f.position[0] + rotated[0]),
                              static_cast<float>(f.position[1] + rotated[1]),
                              static_cast<float>(f.position[2] + rotated[2])};
    views[v].pose.orientation = {static_cast<float>(f.orientation[0]), static_cast<float>(f.orientation[1]),
                                 static_cast<float>(f.orientation[2]), static_cast<float>(f.orientation[3])};
    views[v].fov = {static_cast<float>(-horizontal), static_cast<float>(horizontal), static_cast<float>(half),
                    static_cast<float>(-half)};
    if (st.script.fov_angles.size() == 4) {
      const double deg = M_PI / 180.0;
      const std::vector<double>& a = st.script.fov_angles;
      views[v].fov = {static_cast<float>(a[0] * deg), static_cast<float>(a[1] * deg), static_cast<float>(a[3] * deg),
                      static_cast<float>(a[2] * deg)};  // XrFovf: left, right, up, down
    }
  }
  return XR_SUCCESS;
}

// --- paths and actions ---
XRAPI_ATTR XrResult XRAPI_CALL StringToPath(XrInstance, const char* text, XrPath* path) {
  auto& paths = state().paths;
  const auto it = paths.find(text);
  if (it != paths.end()) {
    *path = it->second;
  } else {
    *path = paths.size() + 1;
    paths[text] = *path;
  }
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL PathToString(XrInstance, XrPath path, std::uint32_t capacity, std::uint32_t* count,
                                            char* buffer) {
  for (const auto& [text, p] : state().paths) {
    if (p != path) continue;
    *count = static_cast<std::uint32_t>(text.size() + 1);
    if (capacity == 0) return XR_SUCCESS;
    if (capacity < *count) return XR_ERROR_SIZE_INSUFFICIENT;
    std::memcpy(buffer, text.c_str(), *count);
    return XR_SUCCESS;
  }
  return XR_ERROR_PATH_INVALID;
}

std::string path_text(XrPath path) {
  for (const auto& [text, p] : state().paths) {
    if (p == path) return text;
  }
  return {};
}

XRAPI_ATTR XrResult XRAPI_CALL CreateActionSet(XrInstance, const XrActionSetCreateInfo*, XrActionSet* set) {
  *set = reinterpret_cast<XrActionSet>(make("XrActionSet"));
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL DestroyActionSet(XrActionSet set) {
  if (!alive(reinterpret_cast<std::uint64_t>(set), "XrActionSet")) return XR_ERROR_HANDLE_INVALID;
  state().live.erase(reinterpret_cast<std::uint64_t>(set));
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL CreateAction(XrActionSet set, const XrActionCreateInfo* info, XrAction* action) {
  if (!alive(reinterpret_cast<std::uint64_t>(set), "XrActionSet")) return XR_ERROR_HANDLE_INVALID;
  const std::uint64_t h = make("XrAction");
  state().actions[h].type = info->actionType;
  *action = reinterpret_cast<XrAction>(h);
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL DestroyAction(XrAction action) {
  if (!alive(reinterpret_cast<std::uint64_t>(action), "XrAction")) return XR_ERROR_HANDLE_INVALID;
  state().live.erase(reinterpret_cast<std::uint64_t>(action));
  state().actions.erase(reinterpret_cast<std::uint64_t>(action));
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL SuggestInteractionProfileBindings(XrInstance,
                                                                 const XrInteractionProfileSuggestedBinding* s) {
  if (path_text(s->interactionProfile) != "/interaction_profiles/oculus/touch_controller") return XR_SUCCESS;
  for (std::uint32_t i = 0; i < s->countSuggestedBindings; ++i) {
    const std::string binding = path_text(s->suggestedBindings[i].binding);
    auto it = state().actions.find(reinterpret_cast<std::uint64_t>(s->suggestedBindings[i].action));
    if (it == state().actions.end()) return XR_ERROR_HANDLE_INVALID;
    if (binding == "/user/hand/left/input/thumbstick") it->second.binding = "left";
    if (binding == "/user/hand/right/input/thumbstick") it->second.binding = "right";
  }
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL AttachSessionActionSets(XrSession session, const XrSessionActionSetsAttachInfo*) {
  return session == state().session ? XR_SUCCESS : XR_ERROR_HANDLE_INVALID;
}

XRAPI_ATTR XrResult XRAPI_CALL SyncActions(XrSession session, const XrActionsSyncInfo*) {
  if (session != state().session) return XR_ERROR_HANDLE_INVALID;
  return state().polled_state == XR_SESSION_STATE_FOCUSED ? XR_SUCCESS : XR_SESSION_NOT_FOCUSED;
}

XRAPI_ATTR XrResult XRAPI_CALL GetCurrentInteractionProfile(XrSession, XrPath, XrInteractionProfileState* profile) {
  XrPath touch = XR_NULL_PATH;
  if (state().script.controllers)
    StringToPath(state().instance, "/interaction_profiles/oculus/touch_controller", &touch);
  profile->interactionProfile = touch;
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL GetActionStateVector2f(XrSession, const XrActionStateGetInfo* info,
                                                      XrActionStateVector2f* out) {
  State& st = state();
  const auto it = st.actions.find(reinterpret_cast<std::uint64_t>(info->action));
  if (it == st.actions.end()) return XR_ERROR_HANDLE_INVALID;
  if (it->second.type != XR_ACTION_TYPE_VECTOR2F_INPUT) return XR_ERROR_ACTION_TYPE_MISMATCH;
  const bool active =
      st.script.controllers && !it->second.binding.empty() && st.polled_state == XR_SESSION_STATE_FOCUSED;
  out->isActive = active ? XR_TRUE : XR_FALSE;
  out->changedSinceLastSync = XR_FALSE;
  out->currentState = {0, 0};
  if (active) {
    const Frame& f = frame_at(st.waited == 0 ? 0 : st.waited - 1);
    const float* stick = it->second.binding == "left" ? f.left_stick : f.right_stick;
    out->currentState = {stick[0], stick[1]};
  }
  return XR_SUCCESS;
}

struct Entry {
  const char* name;
  PFN_xrVoidFunction function;
};

#define SOL_ENTRY(name) \
  { "xr" #name, reinterpret_cast<PFN_xrVoidFunction>(name) }
const Entry kEntries[] = {
    SOL_ENTRY(EnumerateInstanceExtensionProperties),
    SOL_ENTRY(CreateInstance),
    SOL_ENTRY(DestroyInstance),
    SOL_ENTRY(GetInstanceProperties),
    SOL_ENTRY(ResultToString),
    SOL_ENTRY(GetSystem),
    SOL_ENTRY(GetSystemProperties),
    SOL_ENTRY(GetVulkanGraphicsRequirements2KHR),
    SOL_ENTRY(CreateVulkanInstanceKHR),
    SOL_ENTRY(GetVulkanGraphicsDevice2KHR),
    SOL_ENTRY(CreateVulkanDeviceKHR),
    SOL_ENTRY(EnumerateViewConfigurations),
    SOL_ENTRY(EnumerateViewConfigurationViews),
    SOL_ENTRY(EnumerateEnvironmentBlendModes),
    SOL_ENTRY(CreateSession),
    SOL_ENTRY(DestroySession),
    SOL_ENTRY(BeginSession),
    SOL_ENTRY(EndSession),
    SOL_ENTRY(RequestExitSession),
    SOL_ENTRY(PollEvent),
    SOL_ENTRY(EnumerateReferenceSpaces),
    SOL_ENTRY(CreateReferenceSpace),
    SOL_ENTRY(DestroySpace),
    SOL_ENTRY(EnumerateSwapchainFormats),
    SOL_ENTRY(CreateSwapchain),
    SOL_ENTRY(DestroySwapchain),
    SOL_ENTRY(EnumerateSwapchainImages),
    SOL_ENTRY(AcquireSwapchainImage),
    SOL_ENTRY(WaitSwapchainImage),
    SOL_ENTRY(ReleaseSwapchainImage),
    SOL_ENTRY(WaitFrame),
    SOL_ENTRY(BeginFrame),
    SOL_ENTRY(EndFrame),
    SOL_ENTRY(LocateViews),
    SOL_ENTRY(StringToPath),
    SOL_ENTRY(PathToString),
    SOL_ENTRY(CreateActionSet),
    SOL_ENTRY(DestroyActionSet),
    SOL_ENTRY(CreateAction),
    SOL_ENTRY(DestroyAction),
    SOL_ENTRY(SuggestInteractionProfileBindings),
    SOL_ENTRY(AttachSessionActionSets),
    SOL_ENTRY(SyncActions),
    SOL_ENTRY(GetCurrentInteractionProfile),
    SOL_ENTRY(GetActionStateVector2f),
};
#undef SOL_ENTRY

XRAPI_ATTR XrResult XRAPI_CALL GetInstanceProcAddr(XrInstance instance, const char* name,
                                                   PFN_xrVoidFunction* function) {
  const std::string n = name;
  if (n == "xrGetInstanceProcAddr") {
    *function = reinterpret_cast<PFN_xrVoidFunction>(GetInstanceProcAddr);
    return XR_SUCCESS;
  }
  for (const Entry& e : kEntries) {
    if (n != e.name) continue;
    // Without an instance only the functions that create one are available.
    if (instance == XR_NULL_HANDLE && n != "xrEnumerateInstanceExtensionProperties" && n != "xrCreateInstance") break;
    if (n.find("Vulkan") != std::string::npos && state().script.mode == "no_vulkan") break;
    *function = e.function;
    return XR_SUCCESS;
  }
  *function = nullptr;
  return instance == XR_NULL_HANDLE && n != "xrEnumerateApiLayerProperties" ? XR_ERROR_HANDLE_INVALID
                                                                            : XR_ERROR_FUNCTION_UNSUPPORTED;
}

}  // namespace

extern "C" XrResult xrNegotiateLoaderRuntimeInterface(const XrNegotiateLoaderInfo* loaderInfo,
                                                      XrNegotiateRuntimeRequest* runtimeRequest) {
  if (loaderInfo == nullptr || runtimeRequest == nullptr ||
      loaderInfo->structType != XR_LOADER_INTERFACE_STRUCT_LOADER_INFO ||
      runtimeRequest->structType != XR_LOADER_INTERFACE_STRUCT_RUNTIME_REQUEST || loaderInfo->minInterfaceVersion > 1 ||
      loaderInfo->maxInterfaceVersion < 1) {
    return XR_ERROR_INITIALIZATION_FAILED;
  }
  state().script = load_script();
  runtimeRequest->runtimeInterfaceVersion = 1;
  runtimeRequest->runtimeApiVersion = XR_CURRENT_API_VERSION;
  runtimeRequest->getInstanceProcAddr = GetInstanceProcAddr;
  return XR_SUCCESS;
}
