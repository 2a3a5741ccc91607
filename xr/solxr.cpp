// solxr: stands you inside Sol with a headset. Both eyes are rendered by
// the Vulkan ray-marcher (sol::vk::MarchRenderer) in one dispatch on the
// device the OpenXR runtime asks for (XR_KHR_vulkan_enable2) and blitted
// into each eye's swapchain image, two frames in flight (device_frames.hpp);
// head poses become Sol eyes by the exponential map at the base observer
// (eye_pose.hpp); the left thumbstick walks along geodesics, the right one
// turns. This file is the OpenXR session and its frame loop.
//
//   solxr --scene plane
//   solxr --scene lattice-balls --frames 600 --stats
#include <vulkan/vulkan.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>
#define XR_USE_GRAPHICS_API_VULKAN
#include <openxr/openxr.h>
#include <openxr/openxr_platform.h>
#include <openxr/openxr_reflection.h>

#include <sol/sol.hpp>
#include <sol/vk/buffer.hpp>
#include <sol/vk/context.hpp>
#include <sol/vk/error.hpp>
#include <sol/vk/image.hpp>
#include <sol/vk/march.hpp>

#include "image_file.hpp"
#include "command_line.hpp"
#include "device_frames.hpp"
#include "eye_pose.hpp"
#include "adaptive_scale.hpp"
#include "frame_stats.hpp"
#include "refinement.hpp"
#include "renderers.hpp"
#include "srgb.hpp"

namespace {

using sol::xr::begin_transfer_to;
using sol::xr::end_transfer_to;
using sol::xr::FrameClock;
using sol::xr::FramePlan;
using sol::xr::kFoveaLevels;
using sol::xr::kFramesInFlight;

struct Options {
  std::string scene = "plane", reference = "local";
  double scale = 1.0, speed = 1.0, turn_rate = 90.0;
  sol::cli::IntegratorOptions flow;
  int width = 0, height = 0;  // 0: the runtime's recommendation
  long frames = 0;            // 0: until the runtime ends the session
  bool stats = false, validation = false;
  std::string copy = "auto";  // device: kernel image blitted into the swapchain image; host: through the host
  sol::cli::SceneOverrides overrides;  // camera and limits (no --fov: the runtime's)
  double render_scale = 1.0, min_scale = 0.25;
  std::string adaptive = "on";
  int refine = 16;  // samples a still head accumulates (0: off)
  std::string foveation = "off";
};

// The command line; exits 0 after --help and 2 on bad usage.
void add_options(sol::cli::CommandLine& cl, Options& o) {
  cl.add_text("--scene", o.scene, "NAME|FILE",
              "a preset (" + sol::cli::preset_list() +
                  ") or a JSON scene file (default plane); quotient and lights come from the scene, as for solrender");
  o.overrides.add_to(cl, "base observer", false);
  o.flow.add_to(cl);
  cl.add_integer("--width", o.width, 1, 16384, "W", "per-eye image width, 1..16384 (default: the runtime's recommendation)");
  cl.add_integer("--height", o.height, 1, 16384, "H", "per-eye image height, 1..16384 (default: the runtime's recommendation)");
  cl.add_number("--scale", o.scale, "S", "Sol units per metre of head motion, [1e-6, 1e6] (default 1)",
                sol::cli::in_range(1e-6, 1e6));
  cl.add_number("--speed", o.speed, "V", "walking speed, Sol units per second at full stick, [-1e6, 1e6] (default 1)",
                sol::cli::in_range(-1e6, 1e6));
  cl.add_number("--turn-rate", o.turn_rate, "DEG", "turning rate, degrees per second at full stick, [-1e6, 1e6] (default 90)",
                sol::cli::in_range(-1e6, 1e6));
  cl.add_choice("--reference", o.reference, {"local", "stage"}, "the reference space head poses are in (default local)");
  cl.add_integer("--frames", o.frames, 1, 1 << 30, "N",
                 "ask the runtime to end the session after N frames (default: run until the runtime ends it)");
  cl.add_choice("--copy", o.copy, {"auto", "device", "host"},
                "how an eye reaches its swapchain image: device = the kernel's image blitted on the GPU (no host round "
                "trip), host = read back and uploaded; auto (default) = device when the formats allow the blit");
  cl.add_number("--render-scale", o.render_scale, "S",
                "render each eye at S times its size, (0, 1], then upscale (default 1; where --adaptive starts)",
                sol::cli::in_unit_interval());
  cl.add_choice("--adaptive", o.adaptive, {"on", "off"},
                "adapt the render scale to hold the runtime's display period (default on; device copy only)");
  cl.add_number("--min-scale", o.min_scale, "S", "lowest adaptive scale, (0, 1] (default 0.25)",
                sol::cli::in_unit_interval());
  cl.add_integer("--refine", o.refine, 0, 4096, "N",
                 "when the head and the observer have been still for 0.25 s: render at full size, then accumulate up "
                 "to N jittered samples per pixel (as solview --refine); 0: off (default 16; device copy only)");
  cl.add_choice("--foveation", o.foveation, {"off", "on"},
                "fixed foveated rendering: around each eye's centre of view full resolution, then half the rays "
                "(1/sqrt 2 the resolution), then a quarter in the periphery, each blitted up over the one outside "
                "it (default off; device copy only)");
  cl.add_flag("--stats", o.stats,
              "print at exit 'stereo frames: N, mean X ms, p99 Y ms, missed Z' (the time between frames' ends on the "
              "device; missed: device work plus host recording over the display period) and the work per frame");
  cl.add_flag("--validation", o.validation, "enable the Vulkan validation layer; validation errors fail the run");
  cl.set_footer(
      "Head motion moves the eyes along geodesics from the base observer (the scene camera); the left\n"
      "thumbstick walks, the right one turns. The field of view and the eye separation come from the\n"
      "runtime. Exit status: 0 when the session ended normally, 1 when there is no runtime, no headset or\n"
      "no Vulkan support, or on an error, 2 for bad options.");
}

sol::Scene load_scene(const sol::cli::CommandLine& cl, const Options& o) {
  sol::Scene scene;
  try {
    scene = sol::cli::scene_argument(o.scene);
    o.overrides.apply(scene);
    sol::validate(scene);
  } catch (const std::exception& e) {
    cl.fail(e.what());
  }
  return scene;
}

// ---------------------------------------------------------------------------
// OpenXR errors.

/// An OpenXR failure; the message names the call and the result.
class XrError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The result's name (XR_ERROR_RUNTIME_UNAVAILABLE, ...), from the headers'
/// reflection list: also when there is no instance to ask.
std::string result_name(XrResult result) {
#define SOL_XR_RESULT_NAME(name, value) \
  case name:                            \
    return #name;
  switch (result) { XR_LIST_ENUM_XrResult(SOL_XR_RESULT_NAME) default : break; }
#undef SOL_XR_RESULT_NAME
  return "XrResult " + std::to_string(static_cast<int>(result));
}

/// Throws XrError unless `result` succeeded (qualified successes such as
/// XR_SESSION_NOT_FOCUSED pass and are returned).
XrResult xr_check(XrResult result, const char* call) {
  if (XR_FAILED(result)) throw XrError(std::string(call) + " failed: " + result_name(result));
  return result;
}

template <class F>
F xr_function(XrInstance instance, const char* name) {
  PFN_xrVoidFunction f = nullptr;
  xr_check(xrGetInstanceProcAddr(instance, name, &f), name);
  return reinterpret_cast<F>(f);
}

/// An OpenXR input or output structure: zeroed, with its type set.
template <class T>
T xr_struct(XrStructureType type) {
  T value{};
  value.type = type;
  return value;
}

// ---------------------------------------------------------------------------

/// Swapchain formats solxr can fill from the renderer's linear float RGBA,
/// and the bytes per texel.
std::size_t texel_size(std::int64_t format) {
  switch (format) {
    case VK_FORMAT_R32G32B32A32_SFLOAT:
      return 16;
    case VK_FORMAT_R8G8B8A8_SRGB:
    case VK_FORMAT_B8G8R8A8_SRGB:
      return 4;
    default:
      return 0;
  }
}

struct Eye {
  XrSwapchain swapchain = XR_NULL_HANDLE;
  std::vector<VkImage> images;
  std::optional<sol::vk::Buffer> staging;  // host copy: the texels on their way up
  std::vector<std::byte> texels;
};

/// The OpenXR objects in creation order; the destructor takes them down in
/// reverse, so every path out (an exception included) leaves nothing behind.
/// The Vulkan context sits between the instance and the session: the session
/// and its swapchains go before the VkDevice, the XrInstance after it.
struct App {
  XrInstance instance = XR_NULL_HANDLE;
  XrSystemId system = XR_NULL_SYSTEM_ID;
  std::optional<sol::vk::Context> context;
  std::optional<sol::vk::MarchRenderer> renderer;
  XrSession session = XR_NULL_HANDLE;
  XrSpace space = XR_NULL_HANDLE;
  std::vector<Eye> eyes;
  std::optional<sol::xr::DeviceFrames> frames;  // device copy: the frames in flight (device_frames.hpp)
  XrActionSet action_set = XR_NULL_HANDLE;
  XrAction move = XR_NULL_HANDLE, turn = XR_NULL_HANDLE;

  App() = default;
  App(const App&) = delete;
  App& operator=(const App&) = delete;
  ~App() {
    if (context) {
      try {
        context->wait_idle();
      } catch (const std::exception&) {
      }
    }
    frames.reset();
    for (Eye& eye : eyes) {
      eye.staging.reset();
      if (eye.swapchain != XR_NULL_HANDLE) xrDestroySwapchain(eye.swapchain);
    }
    if (move != XR_NULL_HANDLE) xrDestroyAction(move);
    if (turn != XR_NULL_HANDLE) xrDestroyAction(turn);
    if (action_set != XR_NULL_HANDLE) xrDestroyActionSet(action_set);
    if (space != XR_NULL_HANDLE) xrDestroySpace(space);
    if (session != XR_NULL_HANDLE) xrDestroySession(session);
    renderer.reset();
    context.reset();
    if (instance != XR_NULL_HANDLE) xrDestroyInstance(instance);
  }
};

void create_instance(App& app) {
  std::uint32_t count = 0;
  XrResult r = xrEnumerateInstanceExtensionProperties(nullptr, 0, &count, nullptr);
  if (XR_FAILED(r)) {
    const char* json = std::getenv("XR_RUNTIME_JSON");
    throw XrError(
        std::string("no OpenXR runtime available (xrEnumerateInstanceExtensionProperties: ") + result_name(r) +
        "): install and activate one (Monado, SteamVR, ...)" +
        (json != nullptr ? std::string(", or check XR_RUNTIME_JSON=") + json : std::string(" or set XR_RUNTIME_JSON")));
  }
  std::vector<XrExtensionProperties> extensions(count, xr_struct<XrExtensionProperties>(XR_TYPE_EXTENSION_PROPERTIES));
  xr_check(xrEnumerateInstanceExtensionProperties(nullptr, count, &count, extensions.data()),
           "xrEnumerateInstanceExtensionProperties");
  const bool vulkan = std::any_of(extensions.begin(), extensions.end(), [](const XrExtensionProperties& e) {
    return std::strcmp(e.extensionName, XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME) == 0;
  });
  if (!vulkan) {
    throw XrError("the OpenXR runtime does not support Vulkan (no " XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME
                  "); solxr needs a runtime with Vulkan support");
  }
  const char* enabled[] = {XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME};
  auto info = xr_struct<XrInstanceCreateInfo>(XR_TYPE_INSTANCE_CREATE_INFO);
  std::snprintf(info.applicationInfo.applicationName, XR_MAX_APPLICATION_NAME_SIZE, "solxr");
  std::snprintf(info.applicationInfo.engineName, XR_MAX_ENGINE_NAME_SIZE, "Sol");
  info.applicationInfo.apiVersion = XR_MAKE_VERSION(1, 0, 0);
  info.enabledExtensionCount = 1;
  info.enabledExtensionNames = enabled;
  xr_check(xrCreateInstance(&info, &app.instance), "xrCreateInstance");

  auto props = xr_struct<XrInstanceProperties>(XR_TYPE_INSTANCE_PROPERTIES);
  xr_check(xrGetInstanceProperties(app.instance, &props), "xrGetInstanceProperties");
  auto system_info = xr_struct<XrSystemGetInfo>(XR_TYPE_SYSTEM_GET_INFO);
  system_info.formFactor = XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY;
  r = xrGetSystem(app.instance, &system_info, &app.system);
  if (r == XR_ERROR_FORM_FACTOR_UNAVAILABLE || r == XR_ERROR_FORM_FACTOR_UNSUPPORTED) {
    throw XrError(std::string("the OpenXR runtime '") + props.runtimeName + "' finds no headset (" + result_name(r) +
                  "): connect one and try again");
  }
  xr_check(r, "xrGetSystem");
  std::fprintf(stderr, "solxr: OpenXR runtime '%s' %u.%u.%u\n", props.runtimeName,
               XR_VERSION_MAJOR(props.runtimeVersion), XR_VERSION_MINOR(props.runtimeVersion),
               XR_VERSION_PATCH(props.runtimeVersion));
}

/// The Vulkan context on the runtime's device: the Context's create infos go
/// through xrCreateVulkanInstanceKHR / xrGetVulkanGraphicsDevice2KHR /
/// xrCreateVulkanDeviceKHR, which add what the runtime needs.
void create_context(App& app, bool validation) {
  const XrInstance instance = app.instance;
  const XrSystemId system = app.system;
  auto requirements_fn =
      xr_function<PFN_xrGetVulkanGraphicsRequirements2KHR>(instance, "xrGetVulkanGraphicsRequirements2KHR");
  auto create_instance_fn = xr_function<PFN_xrCreateVulkanInstanceKHR>(instance, "xrCreateVulkanInstanceKHR");
  auto device_fn = xr_function<PFN_xrGetVulkanGraphicsDevice2KHR>(instance, "xrGetVulkanGraphicsDevice2KHR");
  auto create_device_fn = xr_function<PFN_xrCreateVulkanDeviceKHR>(instance, "xrCreateVulkanDeviceKHR");

  auto requirements = xr_struct<XrGraphicsRequirementsVulkan2KHR>(XR_TYPE_GRAPHICS_REQUIREMENTS_VULKAN2_KHR);
  xr_check(requirements_fn(instance, system, &requirements), "xrGetVulkanGraphicsRequirements2KHR");
  // Sol::vk asks for Vulkan 1.2.
  const XrVersion ours = XR_MAKE_VERSION(1, 2, 0);
  if (requirements.minApiVersionSupported > ours) {
    throw XrError("the OpenXR runtime needs Vulkan " +
                  std::to_string(XR_VERSION_MAJOR(requirements.minApiVersionSupported)) + "." +
                  std::to_string(XR_VERSION_MINOR(requirements.minApiVersionSupported)) +
                  " or later; solxr uses Vulkan 1.2");
  }

  sol::vk::ContextOptions options;
  options.pipeline_cache_dir = sol::vk::default_pipeline_cache_dir();  // compiled kernels kept between runs
  options.validation = validation;
  options.create_instance = [=](const VkInstanceCreateInfo& info, VkInstance* out) {
    auto xr_info = xr_struct<XrVulkanInstanceCreateInfoKHR>(XR_TYPE_VULKAN_INSTANCE_CREATE_INFO_KHR);
    xr_info.systemId = system;
    xr_info.pfnGetInstanceProcAddr = &vkGetInstanceProcAddr;
    xr_info.vulkanCreateInfo = &info;
    VkResult vk_result = VK_SUCCESS;
    xr_check(create_instance_fn(instance, &xr_info, out, &vk_result), "xrCreateVulkanInstanceKHR");
    return vk_result;
  };
  options.choose_physical_device = [=](VkInstance vk_instance) {
    auto get = xr_struct<XrVulkanGraphicsDeviceGetInfoKHR>(XR_TYPE_VULKAN_GRAPHICS_DEVICE_GET_INFO_KHR);
    get.systemId = system;
    get.vulkanInstance = vk_instance;
    VkPhysicalDevice device = VK_NULL_HANDLE;
    xr_check(device_fn(instance, &get, &device), "xrGetVulkanGraphicsDevice2KHR");
    return device;
  };
  options.create_device = [=](VkPhysicalDevice physical, const VkDeviceCreateInfo& info, VkDevice* out) {
    auto xr_info = xr_struct<XrVulkanDeviceCreateInfoKHR>(XR_TYPE_VULKAN_DEVICE_CREATE_INFO_KHR);
    xr_info.systemId = system;
    xr_info.pfnGetInstanceProcAddr = &vkGetInstanceProcAddr;
    xr_info.vulkanPhysicalDevice = physical;
    xr_info.vulkanCreateInfo = &info;
    VkResult vk_result = VK_SUCCESS;
    xr_check(create_device_fn(instance, &xr_info, out, &vk_result), "xrCreateVulkanDeviceKHR");
    return vk_result;
  };
  app.context.emplace(options);
  std::fprintf(stderr, "solxr: Vulkan device '%s'\n", app.context->device_name().c_str());
}

void create_session(App& app, const Options& o) {
  auto binding = xr_struct<XrGraphicsBindingVulkan2KHR>(XR_TYPE_GRAPHICS_BINDING_VULKAN2_KHR);
  binding.instance = app.context->instance();
  binding.physicalDevice = app.context->physical_device();
  binding.device = app.context->device();
  binding.queueFamilyIndex = app.context->queue_family_index();
  binding.queueIndex = 0;
  auto info = xr_struct<XrSessionCreateInfo>(XR_TYPE_SESSION_CREATE_INFO);
  info.next = &binding;
  info.systemId = app.system;
  xr_check(xrCreateSession(app.instance, &info, &app.session), "xrCreateSession");

  auto space_info = xr_struct<XrReferenceSpaceCreateInfo>(XR_TYPE_REFERENCE_SPACE_CREATE_INFO);
  space_info.referenceSpaceType =
      o.reference == "stage" ? XR_REFERENCE_SPACE_TYPE_STAGE : XR_REFERENCE_SPACE_TYPE_LOCAL;
  space_info.poseInReferenceSpace.orientation.w = 1.0f;
  xr_check(xrCreateReferenceSpace(app.session, &space_info, &app.space), "xrCreateReferenceSpace");
}

/// The per-eye width or height: `option` where given, else the runtime's
/// recommendation, checked against what solxr renders (1..16384), the
/// runtime's largest and the device's largest 2D image: a runtime that
/// recommends 0 or 100000 is named, not followed into its own or Vulkan's
/// failure.
std::uint32_t eye_size(int option, const char* flag, const char* what, std::uint32_t recommended, std::uint32_t runtime_max,
                       std::uint32_t device_max) {
  const std::uint32_t most = std::min({std::uint32_t{16384}, runtime_max, device_max});
  const std::string limits = "at most " + std::to_string(most) + " (solxr 16384, the runtime " +
                             std::to_string(runtime_max) + ", the device " + std::to_string(device_max) + ")";
  if (option > 0) {
    if (static_cast<std::uint32_t>(option) > most) {
      throw XrError(std::string(flag) + " " + std::to_string(option) + ": the eye's " + what + " must be " + limits);
    }
    return static_cast<std::uint32_t>(option);
  }
  if (recommended < 1 || recommended > most) {
    throw XrError("the OpenXR runtime recommends an eye " + std::string(what) + " of " + std::to_string(recommended) +
                  ", which must be " + (recommended < 1 ? std::string("at least 1") : limits) +
                  "; give --width and --height");
  }
  return recommended;
}

/// One swapchain per view, in the first format (the runtime's preference
/// comes first) that solxr can fill; images are written by transfer.
std::int64_t create_swapchains(App& app, const Options& o, std::uint32_t& width, std::uint32_t& height) {
  std::uint32_t count = 0;
  xr_check(xrEnumerateViewConfigurationViews(app.instance, app.system, XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO, 0,
                                             &count, nullptr),
           "xrEnumerateViewConfigurationViews");
  std::vector<XrViewConfigurationView> views(count,
                                             xr_struct<XrViewConfigurationView>(XR_TYPE_VIEW_CONFIGURATION_VIEW));
  xr_check(xrEnumerateViewConfigurationViews(app.instance, app.system, XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO, count,
                                             &count, views.data()),
           "xrEnumerateViewConfigurationViews");
  if (views.size() != 2) {
    throw XrError("the OpenXR runtime offers " + std::to_string(views.size()) +
                  " views for the primary stereo configuration; solxr renders 2");
  }

  xr_check(xrEnumerateSwapchainFormats(app.session, 0, &count, nullptr), "xrEnumerateSwapchainFormats");
  std::vector<std::int64_t> formats(count);
  xr_check(xrEnumerateSwapchainFormats(app.session, count, &count, formats.data()), "xrEnumerateSwapchainFormats");
  const auto format = std::find_if(formats.begin(), formats.end(), [](std::int64_t f) { return texel_size(f) != 0; });
  if (format == formats.end()) {
    throw XrError("the OpenXR runtime offers no swapchain format solxr can fill (RGBA32F, RGBA8 sRGB, BGRA8 sRGB)");
  }

  VkPhysicalDeviceProperties device{};
  vkGetPhysicalDeviceProperties(app.context->physical_device(), &device);
  width = eye_size(o.width, "--width", "width", views[0].recommendedImageRectWidth, views[0].maxImageRectWidth,
                   device.limits.maxImageDimension2D);
  height = eye_size(o.height, "--height", "height", views[0].recommendedImageRectHeight, views[0].maxImageRectHeight,
                    device.limits.maxImageDimension2D);
  for (std::size_t v = 0; v < views.size(); ++v) {
    Eye& eye = app.eyes.emplace_back();
    auto info = xr_struct<XrSwapchainCreateInfo>(XR_TYPE_SWAPCHAIN_CREATE_INFO);
    info.usageFlags = XR_SWAPCHAIN_USAGE_TRANSFER_DST_BIT | XR_SWAPCHAIN_USAGE_COLOR_ATTACHMENT_BIT;
    info.format = *format;
    info.sampleCount = 1;
    info.width = width;
    info.height = height;
    info.faceCount = 1;
    info.arraySize = 1;
    info.mipCount = 1;
    xr_check(xrCreateSwapchain(app.session, &info, &eye.swapchain), "xrCreateSwapchain");
    xr_check(xrEnumerateSwapchainImages(eye.swapchain, 0, &count, nullptr), "xrEnumerateSwapchainImages");
    std::vector<XrSwapchainImageVulkan2KHR> images(
        count, xr_struct<XrSwapchainImageVulkan2KHR>(XR_TYPE_SWAPCHAIN_IMAGE_VULKAN2_KHR));
    xr_check(xrEnumerateSwapchainImages(eye.swapchain, count, &count,
                                        reinterpret_cast<XrSwapchainImageBaseHeader*>(images.data())),
             "xrEnumerateSwapchainImages");
    for (const auto& image : images) eye.images.push_back(image.image);
  }
  return *format;
}

/// Whether the GPU can blit the kernel's RGBA32F image into swapchain images
/// of `format` (with conversion to sRGB bytes where the format asks for it).
bool can_blit(const App& app, std::int64_t format) {
  VkFormatProperties src{}, dst{};
  vkGetPhysicalDeviceFormatProperties(app.context->physical_device(), VK_FORMAT_R32G32B32A32_SFLOAT, &src);
  vkGetPhysicalDeviceFormatProperties(app.context->physical_device(), static_cast<VkFormat>(format), &dst);
  return (src.optimalTilingFeatures & VK_FORMAT_FEATURE_BLIT_SRC_BIT) &&
         (dst.optimalTilingFeatures & VK_FORMAT_FEATURE_BLIT_DST_BIT);
}

/// The host copy's staging buffer per eye.
void prepare_host_copy(App& app, std::int64_t format, std::uint32_t width, std::uint32_t height) {
  for (Eye& eye : app.eyes) {
    const std::size_t bytes = static_cast<std::size_t>(width) * height * texel_size(format);
    eye.staging.emplace(*app.context, bytes);
    eye.texels.resize(bytes);
  }
}

/// Thumbstick actions. Bindings are suggested for common controllers; a
/// runtime that rejects a profile or has no controllers leaves the actions
/// inactive, and solxr then has no locomotion.
void create_actions(App& app) {
  auto set_info = xr_struct<XrActionSetCreateInfo>(XR_TYPE_ACTION_SET_CREATE_INFO);
  std::snprintf(set_info.actionSetName, XR_MAX_ACTION_SET_NAME_SIZE, "locomotion");
  std::snprintf(set_info.localizedActionSetName, XR_MAX_LOCALIZED_ACTION_SET_NAME_SIZE, "Locomotion");
  xr_check(xrCreateActionSet(app.instance, &set_info, &app.action_set), "xrCreateActionSet");
  auto action = [&](const char* name, const char* localized, XrAction* out) {
    auto info = xr_struct<XrActionCreateInfo>(XR_TYPE_ACTION_CREATE_INFO);
    info.actionType = XR_ACTION_TYPE_VECTOR2F_INPUT;
    std::snprintf(info.actionName, XR_MAX_ACTION_NAME_SIZE, "%s", name);
    std::snprintf(info.localizedActionName, XR_MAX_LOCALIZED_ACTION_NAME_SIZE, "%s", localized);
    xr_check(xrCreateAction(app.action_set, &info, out), "xrCreateAction");
  };
  action("move", "Walk along geodesics", &app.move);
  action("turn", "Turn", &app.turn);
  auto path = [&](const char* text) {
    XrPath p = XR_NULL_PATH;
    xr_check(xrStringToPath(app.instance, text, &p), "xrStringToPath");
    return p;
  };
  struct Profile {
    const char* profile;
    const char* left;
    const char* right;
  };
  const Profile profiles[] = {
      {"/interaction_profiles/oculus/touch_controller", "/user/hand/left/input/thumbstick",
       "/user/hand/right/input/thumbstick"},
      {"/interaction_profiles/valve/index_controller", "/user/hand/left/input/thumbstick",
       "/user/hand/right/input/thumbstick"},
      {"/interaction_profiles/microsoft/motion_controller", "/user/hand/left/input/thumbstick",
       "/user/hand/right/input/thumbstick"},
      {"/interaction_profiles/htc/vive_controller", "/user/hand/left/input/trackpad",
       "/user/hand/right/input/trackpad"},
  };
  for (const Profile& p : profiles) {
    const XrActionSuggestedBinding bindings[] = {{app.move, path(p.left)}, {app.turn, path(p.right)}};
    auto suggested = xr_struct<XrInteractionProfileSuggestedBinding>(XR_TYPE_INTERACTION_PROFILE_SUGGESTED_BINDING);
    suggested.interactionProfile = path(p.profile);
    suggested.countSuggestedBindings = 2;
    suggested.suggestedBindings = bindings;
    const XrResult r = xrSuggestInteractionProfileBindings(app.instance, &suggested);
    if (XR_FAILED(r)) {
      std::fprintf(stderr, "solxr: the runtime refuses bindings for %s (%s)\n", p.profile, result_name(r).c_str());
    }
  }
  auto attach = xr_struct<XrSessionActionSetsAttachInfo>(XR_TYPE_SESSION_ACTION_SETS_ATTACH_INFO);
  attach.countActionSets = 1;
  attach.actionSets = &app.action_set;
  xr_check(xrAttachSessionActionSets(app.session, &attach), "xrAttachSessionActionSets");
}

/// Walks and turns the base observer by the thumbsticks over `seconds`.
void locomote(App& app, sol::Observer& base, const Options& o, double seconds, bool& announced) {
  XrActiveActionSet active{app.action_set, XR_NULL_PATH};
  auto sync = xr_struct<XrActionsSyncInfo>(XR_TYPE_ACTIONS_SYNC_INFO);
  sync.countActiveActionSets = 1;
  sync.activeActionSets = &active;
  if (xr_check(xrSyncActions(app.session, &sync), "xrSyncActions") != XR_SUCCESS) return;  // not focused
  auto stick = [&](XrAction action) -> std::optional<glm::dvec2> {
    auto get = xr_struct<XrActionStateGetInfo>(XR_TYPE_ACTION_STATE_GET_INFO);
    get.action = action;
    auto state = xr_struct<XrActionStateVector2f>(XR_TYPE_ACTION_STATE_VECTOR2F);
    xr_check(xrGetActionStateVector2f(app.session, &get, &state), "xrGetActionStateVector2f");
    if (!state.isActive) return std::nullopt;
    return glm::dvec2(state.currentState.x, state.currentState.y);
  };
  const std::optional<glm::dvec2> move = stick(app.move), turn = stick(app.turn);
  if (!announced && !move && !turn) {
    std::fprintf(stderr, "solxr: no controllers: no locomotion (head tracking only)\n");
    announced = true;
  }
  if (turn && turn->x != 0.0) base.yaw(turn->x * o.turn_rate * M_PI / 180.0 * seconds);
  if (move && (move->x != 0.0 || move->y != 0.0)) {
    // Stick forward walks along the geodesic straight ahead, sideways strafes.
    const glm::dvec3 local(move->x, 0.0, move->y);
    // The walk stops at the heights the renderer draws (|z| <= 80), with 1
    // to spare for the head's own offsets: a step beyond is not taken.
    const sol::Observer before = base;
    base.move(local, glm::length(local) * o.speed * seconds);
    if (!(std::abs(base.position().z) <= 79.0)) base = before;
  }
}

double now_ms() {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// Acquires the next image of every eye's swapchain and waits until the
/// runtime is done with it; returns them in view order.
std::vector<VkImage> acquire_images(App& app) {
  std::vector<VkImage> targets;
  for (Eye& eye : app.eyes) {
    std::uint32_t index = 0;
    auto acquire = xr_struct<XrSwapchainImageAcquireInfo>(XR_TYPE_SWAPCHAIN_IMAGE_ACQUIRE_INFO);
    xr_check(xrAcquireSwapchainImage(eye.swapchain, &acquire, &index), "xrAcquireSwapchainImage");
    auto wait = xr_struct<XrSwapchainImageWaitInfo>(XR_TYPE_SWAPCHAIN_IMAGE_WAIT_INFO);
    wait.timeout = XR_INFINITE_DURATION;
    xr_check(xrWaitSwapchainImage(eye.swapchain, &wait), "xrWaitSwapchainImage");
    targets.push_back(eye.images.at(index));
  }
  return targets;
}

/// Hands every eye's image back to the runtime (after the frame's
/// submission: the runtime's reads are queued after it).
void release_images(App& app) {
  for (Eye& eye : app.eyes) {
    auto release = xr_struct<XrSwapchainImageReleaseInfo>(XR_TYPE_SWAPCHAIN_IMAGE_RELEASE_INFO);
    xr_check(xrReleaseSwapchainImage(eye.swapchain, &release), "xrReleaseSwapchainImage");
  }
}

/// The host path (--copy host, or a swapchain format the device cannot
/// blit into): render() reads both eyes back, the host converts each to the
/// swapchain's format and one submission uploads them, waited for. Returns
/// the device's time (kernel and upload) in milliseconds.
double render_through_host(App& app, const std::array<sol::Camera, 2>& cameras, const std::vector<VkImage>& targets,
                           std::int64_t format, std::uint32_t width, std::uint32_t height) {
  const sol::RenderResult image =
      app.renderer->render(cameras, {.width = static_cast<int>(width), .height = static_cast<int>(height)});
  // Into the swapchain's format (linear floats, or sRGB-encoded bytes), each eye its half.
  const bool bgr = format == VK_FORMAT_B8G8R8A8_SRGB;
  for (std::size_t v = 0; v < app.eyes.size(); ++v) {
    Eye& eye = app.eyes[v];
    for (std::uint32_t j = 0; j < height; ++j) {
      const float* row = &image.rgba[(static_cast<std::size_t>(j) * 2 * width + v * width) * 4];
      std::byte* out_row = eye.texels.data() + static_cast<std::size_t>(j) * width * texel_size(format);
      if (format == VK_FORMAT_R32G32B32A32_SFLOAT) {
        std::memcpy(out_row, row, static_cast<std::size_t>(width) * 16);
        continue;
      }
      auto* out = reinterpret_cast<std::uint8_t*>(out_row);
      for (std::uint32_t i = 0; i < width; ++i) {
        const float* in = &row[4 * i];
        out[4 * i + 0] = sol::programs::srgb_byte(in[bgr ? 2 : 0]);
        out[4 * i + 1] = sol::programs::srgb_byte(in[1]);
        out[4 * i + 2] = sol::programs::srgb_byte(in[bgr ? 0 : 2]);
        out[4 * i + 3] = 255;
      }
    }
    eye.staging->write(eye.texels);
  }
  const double upload_ms = app.context->submit_and_wait([&](VkCommandBuffer cmd) {
    for (std::size_t v = 0; v < app.eyes.size(); ++v) {
      begin_transfer_to(cmd, targets[v]);
      VkBufferImageCopy region{};
      region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
      region.imageExtent = {width, height, 1};
      vkCmdCopyBufferToImage(cmd, app.eyes[v].staging->handle(), targets[v], VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                             &region);
      end_transfer_to(cmd, targets[v]);
    }
  });
  return image.device_ms + upload_ms;
}

/// What determines a frame's image, for the refinement: both eyes'
/// positions and directions (and the first's window), rounded to 1e-6 so
/// that a head held still within that is still.
std::array<double, 16> view_key(const std::array<sol::Camera, 2>& cameras) {
  const sol::Camera& a = cameras[0];
  const sol::Camera& b = cameras[1];
  const double frustum = a.frustum ? a.frustum->left + 3 * a.frustum->right + 5 * a.frustum->up : 0.0;
  std::array<double, 16> key = {a.position.x, a.position.y, a.position.z, a.forward.x, a.forward.y, a.forward.z,
                                a.up.x,       a.up.y,       a.up.z,       b.position.x, b.position.y, b.position.z,
                                b.forward.x,  b.forward.y,  b.forward.z,  frustum};
  for (double& k : key) k = std::round(k * 1e6);
  return key;
}

/// The Sol eyes of the located views, each with its own, generally
/// off-centre, view window (sol::Frustum); the composition layer's views.
std::array<sol::Camera, 2> eye_cameras(const sol::Scene& scene, const sol::Observer& base, const Options& o,
                                       const std::vector<XrView>& views) {
  std::array<sol::Camera, 2> cameras;
  for (std::size_t v = 0; v < cameras.size(); ++v) {
    const XrView& view = views[v];
    const XrFovf& f = view.fov;
    const sol::Frustum frustum{std::tan(static_cast<double>(f.angleLeft)), std::tan(static_cast<double>(f.angleRight)),
                               std::tan(static_cast<double>(f.angleDown)), std::tan(static_cast<double>(f.angleUp))};
    if (!(frustum.left < frustum.right && frustum.down < frustum.up)) {
      throw XrError("the OpenXR runtime gave view " + std::to_string(v) + " an empty field of view");
    }
    sol::xr::ViewPose pose;
    pose.position = {view.pose.position.x, view.pose.position.y, view.pose.position.z};
    pose.orientation =
        glm::dquat(view.pose.orientation.w, view.pose.orientation.x, view.pose.orientation.y, view.pose.orientation.z);
    // Per frame only the eyes change: the world was prepared once (run).
    sol::Camera camera = sol::xr::eye_camera(base, pose, o.scale, scene.camera);
    camera.frustum = frustum;
    try {
      sol::validate(camera);
    } catch (const sol::InvalidArgument& e) {
      char where[160];
      std::snprintf(where, sizeof where, "view %zu: the head pose at (%g, %g, %g) m (--scale %g) puts the eye where solxr cannot render: ",
                    v, pose.position.x, pose.position.y, pose.position.z, o.scale);
      throw XrError(where + std::string(e.what()));
    }
    cameras[v] = camera;
  }
  return cameras;
}

// The runtime's events: the session state machine (begin when ready, end
// when stopping, `quit` on exiting or loss), `running` between begin and end.
void poll_events(App& app, bool& running, bool& quit) {
  auto event = xr_struct<XrEventDataBuffer>(XR_TYPE_EVENT_DATA_BUFFER);
  while (xr_check(xrPollEvent(app.instance, &event), "xrPollEvent") == XR_SUCCESS) {
    if (event.type == XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED) {
      const auto& changed = reinterpret_cast<const XrEventDataSessionStateChanged&>(event);
      switch (changed.state) {
        case XR_SESSION_STATE_READY: {
          auto begin = xr_struct<XrSessionBeginInfo>(XR_TYPE_SESSION_BEGIN_INFO);
          begin.primaryViewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
          xr_check(xrBeginSession(app.session, &begin), "xrBeginSession");
          running = true;
          std::fprintf(stderr, "solxr: session running\n");
          break;
        }
        case XR_SESSION_STATE_FOCUSED:
          std::fprintf(stderr, "solxr: focused\n");
          break;
        case XR_SESSION_STATE_VISIBLE:
          std::fprintf(stderr, "solxr: visible, not focused\n");
          break;
        case XR_SESSION_STATE_STOPPING:
          xr_check(xrEndSession(app.session), "xrEndSession");
          running = false;
          std::fprintf(stderr, "solxr: session ended\n");
          break;
        case XR_SESSION_STATE_EXITING:
          quit = true;
          break;
        case XR_SESSION_STATE_LOSS_PENDING:
          std::fprintf(stderr, "solxr: the runtime is losing the session; exiting\n");
          quit = true;
          break;
        default:
          break;
      }
    } else if (event.type == XR_TYPE_EVENT_DATA_INSTANCE_LOSS_PENDING) {
      std::fprintf(stderr, "solxr: the runtime is going away; exiting\n");
      quit = true;
    }
    event = xr_struct<XrEventDataBuffer>(XR_TYPE_EVENT_DATA_BUFFER);
  }
}

int run(const Options& o, const sol::Scene& scene) {
  App app;
  create_instance(app);
  create_context(app, o.validation);
  sol::vk::MarchOptions march = sol::programs::march_options({.rk4 = o.flow.rk4(), .rk4_step = o.flow.rk_step});
  // A foveated frame records one dispatch per level: each a call of the renderer's.
  march.frames_in_flight = kFramesInFlight * (o.foveation == "on" ? kFoveaLevels : 1);
  app.renderer.emplace(*app.context, march);
  app.renderer->set_world(scene);  // prepared once: every frame only sends its eyes
  create_session(app, o);
  std::uint32_t width = 0, height = 0;
  const std::int64_t format = create_swapchains(app, o, width, height);
  const bool blit = can_blit(app, format);
  if (o.copy == "device" && !blit) {
    throw XrError("--copy device: the device cannot blit RGBA32F images into the runtime's swapchain format");
  }
  const bool device_copy = o.copy == "device" || (o.copy == "auto" && blit);
  const bool foveation = device_copy && o.foveation == "on";
  if (o.foveation == "on" && !device_copy) {
    std::fprintf(stderr, "solxr: --foveation: the host copy renders every pixel (no foveation)\n");
  }
  if (!device_copy && (o.adaptive == "on" || o.refine > 0)) {
    std::fprintf(stderr, "solxr: the host copy renders every frame at full size, once: no adaptive render scale "
                         "(--adaptive) and no refinement (--refine), which the device copy does\n");
  }
  if (device_copy) {
    app.frames.emplace(*app.context, *app.renderer, width, height, foveation);
  } else {
    prepare_host_copy(app, format, width, height);
  }
  create_actions(app);
  std::fprintf(stderr, "solxr: %zu views of %ux%u, %s copy into the swapchain%s\n", app.eyes.size(), width, height,
               device_copy ? "device" : "host",
               device_copy ? ", both eyes in one submission, 2 frames in flight" : ", waited for");

  sol::Observer base = sol::observer_at(scene);

  bool running = false, quit = false, exit_requested = false, announced = false;
  long frames = 0;
  FrameClock clock;
  // Holding the rate (device copy): the render scale adapts to the display
  // period from the frames' device work and recording, two frames late (a
  // slot's figures are read when it is reused); a still head refines.
  double scale = o.render_scale;
  std::optional<sol::programs::AdaptiveScale> adaptive;
  long adapted = 0;  // frames the adaptive scale has counted
  sol::programs::Refinement refinement(device_copy ? o.refine : 0);
  XrTime last_time = 0;
  while (!quit) {
    poll_events(app, running, quit);
    if (quit) break;
    if (!running) {  // idle until the runtime says ready (or exiting)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
      continue;
    }

    if (o.frames > 0 && frames >= o.frames && !exit_requested) {
      xr_check(xrRequestExitSession(app.session), "xrRequestExitSession");
      exit_requested = true;
    }
    // The loop's only waits: the runtime's pacing here and its swapchain
    // images below (and a slot's fence, for the frame kFramesInFlight back).
    auto wait = xr_struct<XrFrameWaitInfo>(XR_TYPE_FRAME_WAIT_INFO);
    auto frame = xr_struct<XrFrameState>(XR_TYPE_FRAME_STATE);
    xr_check(xrWaitFrame(app.session, &wait, &frame), "xrWaitFrame");
    auto begin = xr_struct<XrFrameBeginInfo>(XR_TYPE_FRAME_BEGIN_INFO);
    xr_check(xrBeginFrame(app.session, &begin), "xrBeginFrame");

    const double seconds = last_time == 0 ? 0.0 : static_cast<double>(frame.predictedDisplayTime - last_time) * 1e-9;
    last_time = frame.predictedDisplayTime;
    locomote(app, base, o, seconds, announced);

    std::vector<XrCompositionLayerProjectionView> layer_views(app.eyes.size());
    auto layer = xr_struct<XrCompositionLayerProjection>(XR_TYPE_COMPOSITION_LAYER_PROJECTION);
    const XrCompositionLayerBaseHeader* layers[] = {reinterpret_cast<const XrCompositionLayerBaseHeader*>(&layer)};
    auto end = xr_struct<XrFrameEndInfo>(XR_TYPE_FRAME_END_INFO);
    end.displayTime = frame.predictedDisplayTime;
    end.environmentBlendMode = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
    bool rendered = false;
    if (frame.shouldRender) {
      const double period_ms = static_cast<double>(frame.predictedDisplayPeriod) * 1e-6;
      // This frame's slot comes back: the frame kFramesInFlight back, done and counted.
      if (app.frames && app.frames->retire(frames, clock) && o.adaptive == "on" && clock.last_adaptive &&
          period_ms > 0.0) {
        if (!adaptive || adaptive->target_ms() != period_ms) adaptive.emplace(period_ms, o.min_scale);
        scale = adaptive->next(scale, adapted++, clock.last_work_ms);
      }
      // The head pose as late as the frame allows: for this frame's
      // predicted display time, after the slot's wait.
      auto locate = xr_struct<XrViewLocateInfo>(XR_TYPE_VIEW_LOCATE_INFO);
      locate.viewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
      locate.displayTime = frame.predictedDisplayTime;
      locate.space = app.space;
      auto view_state = xr_struct<XrViewState>(XR_TYPE_VIEW_STATE);
      std::uint32_t count = 0;
      std::vector<XrView> views(app.eyes.size(), xr_struct<XrView>(XR_TYPE_VIEW));
      xr_check(xrLocateViews(app.session, &locate, &view_state, static_cast<std::uint32_t>(views.size()), &count,
                             views.data()),
               "xrLocateViews");
      const XrViewStateFlags needed = XR_VIEW_STATE_ORIENTATION_VALID_BIT | XR_VIEW_STATE_POSITION_VALID_BIT;
      if ((view_state.viewStateFlags & needed) == needed && count == views.size()) {
        const std::array<sol::Camera, 2> cameras = eye_cameras(scene, base, o, views);
        const std::vector<VkImage> targets = acquire_images(app);
        if (app.frames) {
          // A still head (and observer) refines; a move starts again at the
          // adaptive scale, which forgets the full-size frames.
          if (!refinement.update(view_key(cameras), seconds, scale)) {
            adaptive.reset();
            adapted = 0;
          }
          FramePlan plan{.scale = scale, .foveated = foveation};
          if (const auto sample = refinement.sample()) {
            plan = FramePlan{.scale = 1.0, .sample = sol::vk::PixelSample{sample->offset, sample->weight}};
          } else if (refinement.reuse()) {
            plan = FramePlan{.scale = 1.0, .reuse = true};
          }
          app.frames->submit(frames, cameras, targets, plan, clock.chain, period_ms, !plan.sample && !plan.reuse);
          refinement.shown();
        } else {
          const double started = now_ms();
          const double work_ms = render_through_host(app, cameras, targets, format, width, height);
          const double finished = now_ms();
          const std::optional<double> interval =
              clock.chain && clock.last_end_ms ? std::optional<double>(finished - *clock.last_end_ms) : std::nullopt;
          clock.stats.add(interval, work_ms, finished - started - work_ms, period_ms);
          clock.last_end_ms = finished;
        }
        release_images(app);
        for (std::size_t v = 0; v < app.eyes.size(); ++v) {
          XrCompositionLayerProjectionView& lv = layer_views[v];
          lv = xr_struct<XrCompositionLayerProjectionView>(XR_TYPE_COMPOSITION_LAYER_PROJECTION_VIEW);
          lv.pose = views[v].pose;
          lv.fov = views[v].fov;
          lv.subImage.swapchain = app.eyes[v].swapchain;
          lv.subImage.imageRect = {{0, 0}, {static_cast<std::int32_t>(width), static_cast<std::int32_t>(height)}};
          lv.subImage.imageArrayIndex = 0;
        }
        layer.space = app.space;
        layer.viewCount = static_cast<std::uint32_t>(layer_views.size());
        layer.views = layer_views.data();
        end.layerCount = 1;
        end.layers = layers;
        rendered = true;
      }
    }
    clock.chain = rendered;  // a frame not rendered breaks the chain of intervals
    xr_check(xrEndFrame(app.session, &end), "xrEndFrame");
    ++frames;
  }
  // The frames still in flight: waited for and counted, in order.
  if (app.frames) app.frames->drain(frames, clock);

  std::fprintf(stderr, "solxr: %ld frames\n", frames);
  if (o.stats) {
    std::printf("%s\n", clock.stats.summary("stereo").c_str());
    std::printf("solxr: %ux%u per eye on '%s', %s copy: %s\n", width, height, app.context->device_name().c_str(),
                device_copy ? "device" : "host", clock.stats.details().c_str());
    if (device_copy && clock.stats.frames() > 0) {
      std::printf("solxr: render scale %.2f at the end, mean %.2f\n", scale,
                  clock.scale_sum / static_cast<double>(clock.stats.frames()));
    }
  }
  if (o.validation) {
    const std::size_t errors = app.context->validation_errors().size();
    if (errors > 0) {
      std::fprintf(stderr, "solxr: %zu Vulkan validation errors\n", errors);
      return 1;
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  sol::programs::install_texture_reader();  // scene files' "texture" keys
  sol::cli::CommandLine cl("solxr", "[options]",
                           "Shows a Sol scene in an OpenXR headset (XR_KHR_vulkan_enable2): every pixel of each eye "
                           "follows a Sol geodesic.");
  Options options;
  add_options(cl, options);
  cl.parse(argc, argv);
  if ((options.width == 0) != (options.height == 0)) cl.fail("options --width and --height go together");
  const sol::Scene scene = load_scene(cl, options);
  try {
    return run(options, scene);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "solxr: %s\n", e.what());
    return 1;
  }
}
