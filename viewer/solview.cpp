// solview: the real-time viewer. A GLFW window with a Vulkan swapchain that
// shows the march kernel's image of a Sol scene, and controls to walk along
// geodesics (viewer/controls.hpp). A thin presenter: the kernel
// (sol::vk::MarchRenderer::record) writes each frame straight into the
// swapchain image (sRGB-encoded, into a storage-capable UNORM swapchain) when
// it renders at the window's size, else an RGBA float image at the render
// scale, which is blitted (scaled, sRGB-encoded) into an sRGB swapchain image.
// See "How solview presents a frame" in viewer/README.md.
//
//   solview --scene sandwich
//   solview --scene plane --size 320x180 --frames 60 --screenshot last.png
#include <GLFW/glfw3.h>  // after vulkan_core.h (GLFW_INCLUDE_VULKAN is defined by CMake)

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <sol/sol.hpp>
#include <sol/vk/context.hpp>
#include <sol/vk/error.hpp>
#include <sol/vk/image.hpp>
#include <sol/vk/march.hpp>

#include "command_line.hpp"
#include "controls.hpp"
#include "image_file.hpp"

namespace {

using sol::viewer::Key;

const char* kControls =
    "controls:\n"
    "  W / S          move forward / back along the geodesic you look along\n"
    "  A / D          move left / right along the geodesic in that direction\n"
    "  R / F          move up / down along the geodesic in that direction\n"
    "  Shift          move 5x faster\n"
    "  arrows, drag   turn (left mouse button held: drag to look around)\n"
    "  Q / E          roll left / right\n"
    "  Home           back to the scene's camera\n"
    "  Tab            next preset scene\n"
    "  T              stereo side by side on / off\n"
    "  Y              vsync on / off\n"
    "  + / -          render scale up / down (fixes the scale: adaptive off)\n"
    "  G              adaptive render scale on / off\n"
    "  P              screenshot to solview-NNNN.png (the frame as shown)\n"
    "  F11            fullscreen on / off\n"
    "  H              print these controls\n"
    "  Esc            quit\n"
    "The frame is parallel-transported along every move; in the quotient\n"
    "(lattice-balls) the observer is teleported back into the fundamental domain.\n";

void print_usage(std::FILE* out) {
  std::fprintf(out,
               "usage: solview [options]\n"
               "Walks through Thurston's Sol geometry in a window: every pixel follows a Sol geodesic.\n\n"
               "  --scene NAME|FILE     a preset (%s) or a JSON scene file (default plane)\n"
               "  --size WxH            window size in pixels (default 640x360)\n"
               "  --scale S             render at S times the window size, (0, 1] (default 1), then upscale\n"
               "  --target-fps F        adapt the render scale to hold F frames per second\n"
               "  --min-scale S         lowest adaptive scale, (0, 1] (default 0.05)\n"
               "  --vsync on|off        wait for the display's refresh (default on)\n"
               "  --present auto|blit   auto (default): the kernel writes straight into the swapchain image\n"
               "                        at render scale 1 when the surface allows it; blit: always through\n"
               "                        an RGBA float image and a blit\n"
               "  --fullscreen          start fullscreen\n"
               "  --stereo              both eyes side by side (each eye half the width)\n"
               "  --ipd D               eye separation in Sol units (default 0.064)\n"
               "  --frames N            exit after N frames\n"
               "  --screenshot FILE     at exit, write the last frame as shown (window size) to FILE\n"
               "  --script FILE         replay timed inputs: lines 'TIME down KEY', 'TIME up KEY',\n"
               "                        'TIME mouse DX DY' (TIME in seconds; replays step 1/60 s per frame)\n"
               "  --record DIR          write every frame as DIR/frame-NNNNNN.png\n"
               "  --state FILE          at exit, write the observer's position and frame to FILE\n"
               "  --validation          enable the Vulkan validation layer; its errors make the exit status 3\n"
               "  --help                this text\n\n"
               "%s\n"
               "Script key names: %s.\n\n"
               "Exit status: 0 on success, 1 when no window can be opened (no display), 2 for bad options,\n"
               "3 for validation errors, 4 for other failures.\n",
               [] {
                 static std::string names;
                 for (const std::string& n : sol::preset_names()) names += (names.empty() ? "" : ", ") + n;
                 return names.c_str();
               }(),
               kControls, sol::viewer::key_names().c_str());
}

const sol::cli::Arguments kArgs("solview");

[[noreturn]] void fail(const std::string& message, int status = 2) {
  std::fprintf(stderr, "solview: %s\n", message.c_str());
  std::exit(status);
}

struct Options {
  std::string scene = "plane";
  int width = 640, height = 360;
  double scale = 1.0, min_scale = 0.05, ipd = 0.064;
  std::optional<double> target_fps;
  bool vsync = true, fullscreen = false, stereo = false, validation = false;
  bool allow_direct = true;  // --present auto
  long frames = 0;  // 0: until the window closes
  std::string screenshot, script, record, state;
};

Options parse_options(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) fail("option " + arg + " needs a value");
      return argv[++i];
    };
    if (arg == "--help" || arg == "-h") {
      print_usage(stdout);
      std::exit(0);
    } else if (arg == "--scene") {
      o.scene = value();
    } else if (arg == "--size") {
      const std::string v = value();
      const auto x = v.find('x');
      if (x == std::string::npos) fail("option --size expects WxH like 640x360, got '" + v + "'");
      o.width = static_cast<int>(kArgs.integer(v.substr(0, x), "--size (width)", 1, 16384));
      o.height = static_cast<int>(kArgs.integer(v.substr(x + 1), "--size (height)", 1, 16384));
    } else if (arg == "--scale") {
      o.scale = kArgs.number(value(), arg);
      if (!(o.scale > 0.0 && o.scale <= 1.0)) fail("option --scale must be in (0, 1], got " + std::string(argv[i]));
    } else if (arg == "--min-scale") {
      o.min_scale = kArgs.number(value(), arg);
      if (!(o.min_scale > 0.0 && o.min_scale <= 1.0)) fail("option --min-scale must be in (0, 1], got " + std::string(argv[i]));
    } else if (arg == "--target-fps") {
      o.target_fps = kArgs.number(value(), arg);
      if (!(*o.target_fps > 0.0)) fail("option --target-fps must be > 0, got " + std::string(argv[i]));
    } else if (arg == "--vsync") {
      const std::string v = value();
      if (v != "on" && v != "off") fail("option --vsync expects on or off, got '" + v + "'");
      o.vsync = v == "on";
    } else if (arg == "--present") {
      const std::string v = value();
      if (v != "auto" && v != "blit") fail("option --present expects auto or blit, got '" + v + "'");
      o.allow_direct = v == "auto";
    } else if (arg == "--fullscreen") {
      o.fullscreen = true;
    } else if (arg == "--stereo") {
      o.stereo = true;
    } else if (arg == "--ipd") {
      o.ipd = kArgs.number(value(), arg);
      if (o.ipd < 0.0) fail("option --ipd must be >= 0, got " + std::string(argv[i]));
    } else if (arg == "--frames") {
      o.frames = kArgs.integer(value(), arg, 1, 100000000);
    } else if (arg == "--screenshot") {
      o.screenshot = value();
    } else if (arg == "--script") {
      o.script = value();
    } else if (arg == "--record") {
      o.record = value();
    } else if (arg == "--state") {
      o.state = value();
    } else if (arg == "--validation") {
      o.validation = true;
    } else {
      fail("unknown option '" + arg + "' (see solview --help)");
    }
  }
  return o;
}

sol::Scene load(const std::string& arg) {
  sol::Scene scene = sol::cli::scene_argument(arg);
  sol::validate(scene);
  return scene;
}

sol::Observer observer_for(const sol::Scene& scene) {
  sol::Observer o(scene.camera.position, scene.camera.forward, scene.camera.up);
  if (scene.quotient != sol::Quotient::None) o.bind(sol::Lattice::golden());  // stays in D
  return o;
}

std::optional<Key> key_of(int glfw_key) {
  switch (glfw_key) {
    case GLFW_KEY_W: return Key::W;
    case GLFW_KEY_S: return Key::S;
    case GLFW_KEY_A: return Key::A;
    case GLFW_KEY_D: return Key::D;
    case GLFW_KEY_R: return Key::R;
    case GLFW_KEY_F: return Key::F;
    case GLFW_KEY_Q: return Key::Q;
    case GLFW_KEY_E: return Key::E;
    case GLFW_KEY_UP: return Key::Up;
    case GLFW_KEY_DOWN: return Key::Down;
    case GLFW_KEY_LEFT: return Key::Left;
    case GLFW_KEY_RIGHT: return Key::Right;
    case GLFW_KEY_LEFT_SHIFT:
    case GLFW_KEY_RIGHT_SHIFT: return Key::Shift;
    case GLFW_KEY_TAB: return Key::Tab;
    case GLFW_KEY_HOME: return Key::Home;
    case GLFW_KEY_T: return Key::T;
    case GLFW_KEY_Y: return Key::Y;
    case GLFW_KEY_P: return Key::P;
    case GLFW_KEY_H: return Key::H;
    case GLFW_KEY_G: return Key::G;
    case GLFW_KEY_EQUAL:
    case GLFW_KEY_KP_ADD: return Key::Plus;
    case GLFW_KEY_MINUS:
    case GLFW_KEY_KP_SUBTRACT: return Key::Minus;
    case GLFW_KEY_F11: return Key::F11;
    case GLFW_KEY_ESCAPE: return Key::Escape;
    default: return std::nullopt;
  }
}

std::string glfw_error;
void on_glfw_error(int, const char* description) { glfw_error = description ? description : "unknown GLFW error"; }

// The viewer's state that callbacks reach through the window's user pointer.
struct App {
  Options options;
  std::vector<std::string> presets = [] {  // the presets the kernel renders (MarchRenderer::supports)
    std::vector<std::string> names;
    for (const std::string& n : sol::preset_names()) {
      if (sol::vk::MarchRenderer::supports(sol::preset_scene(n))) names.push_back(n);
    }
    return names;
  }();
  sol::Scene scene;
  std::string scene_name;
  sol::Observer observer;
  sol::viewer::Controls controls;
  double scale = 1.0;
  bool adaptive = false, stereo = false, vsync = true, fullscreen = false;
  bool swapchain_dirty = false, want_screenshot = false, quit = false;
  bool world_changed = true;  // the renderer needs set_world(scene) before the next frame
  int screenshots = 0;
  bool dragging = false;
  double last_x = 0, last_y = 0;
  int windowed[4] = {0, 0, 640, 360};
  GLFWwindow* window = nullptr;

  void set_scene(const std::string& name) {
    scene = load(name);
    scene_name = name;
    observer = observer_for(scene);
    world_changed = true;
  }

  // Keys with an effect on press (the held ones act in Controls::step).
  void press(Key k) {
    switch (k) {
      case Key::Home: observer = observer_for(scene); break;
      case Key::Tab: {
        auto it = std::find(presets.begin(), presets.end(), scene_name);
        const std::size_t next = it == presets.end() ? 0 : (static_cast<std::size_t>(it - presets.begin()) + 1) % presets.size();
        set_scene(presets[next]);
        break;
      }
      case Key::T: stereo = !stereo; break;
      case Key::Y: vsync = !vsync; swapchain_dirty = true; break;
      case Key::G: adaptive = !adaptive; break;
      case Key::Plus: adaptive = false; scale = std::min(1.0, scale * 1.25); break;
      case Key::Minus: adaptive = false; scale = std::max(options.min_scale, scale / 1.25); break;
      case Key::P: want_screenshot = true; break;
      case Key::H: std::printf("%s", kControls); std::fflush(stdout); break;
      case Key::F11: toggle_fullscreen(); break;
      case Key::Escape: quit = true; break;
      default: break;
    }
  }
  void key(Key k, bool down) {
    if (down && !controls.held(k)) press(k);
    controls.key(k, down);
  }
  void toggle_fullscreen() {
    if (!window) return;
    fullscreen = !fullscreen;
    if (fullscreen) {
      glfwGetWindowPos(window, &windowed[0], &windowed[1]);
      glfwGetWindowSize(window, &windowed[2], &windowed[3]);
      GLFWmonitor* monitor = glfwGetPrimaryMonitor();
      const GLFWvidmode* mode = monitor ? glfwGetVideoMode(monitor) : nullptr;
      if (mode) glfwSetWindowMonitor(window, monitor, 0, 0, mode->width, mode->height, mode->refreshRate);
    } else {
      glfwSetWindowMonitor(window, nullptr, windowed[0], windowed[1], windowed[2], windowed[3], 0);
    }
    swapchain_dirty = true;
  }
};

App& app_of(GLFWwindow* w) { return *static_cast<App*>(glfwGetWindowUserPointer(w)); }

// ---------------------------------------------------------------------------
// Presentation: surface, swapchain and the per-frame commands.

struct Presenter {
  sol::vk::Context& context;
  VkSurfaceKHR surface = VK_NULL_HANDLE;
  VkSwapchainKHR swapchain = VK_NULL_HANDLE;
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkExtent2D extent{};
  std::vector<VkImage> images;
  std::vector<VkImageView> views;  // direct: one per swapchain image, the kernel's storage target
  // The direct path: the kernel writes the frame straight into the swapchain
  // image. It needs a UNORM format (sRGB formats are never storage-capable;
  // the kernel sRGB-encodes) with STORAGE and TRANSFER_SRC usage (screenshots
  // then always take the frame as shown). Scaled frames need the blit, and
  // the blit sRGB-encodes only into an sRGB swapchain: each path has its own
  // swapchain, re-created when the path changes.
  bool prefer_direct = false;   // the next swapchain is for the direct path when the surface allows it
  bool direct_capable = false;  // the surface allows it (known after create_swapchain)
  bool direct = false;          // the current swapchain is the direct path's
  std::vector<VkSemaphore> rendered;  // one per swapchain image: present waits on it
  VkSemaphore acquired = VK_NULL_HANDLE;
  VkFence frame_done = VK_NULL_HANDLE;
  VkCommandPool pool = VK_NULL_HANDLE;
  VkCommandBuffer commands = VK_NULL_HANDLE;
  bool linear_blit = false;
  bool can_capture = false;  // swapchain images may be copied out (TRANSFER_SRC)
  // The shown frame copied to the host (screenshots, --record): a host-visible buffer.
  VkBuffer capture = VK_NULL_HANDLE;
  VkDeviceMemory capture_memory = VK_NULL_HANDLE;
  void* capture_data = nullptr;
  VkDeviceSize capture_size = 0;

  explicit Presenter(sol::vk::Context& c) : context(c) {}
  Presenter(const Presenter&) = delete;
  Presenter& operator=(const Presenter&) = delete;

  void init(GLFWwindow* window, bool vsync) {
    VkDevice device = context.device();
    sol::vk::check(glfwCreateWindowSurface(context.instance(), window, nullptr, &surface), "glfwCreateWindowSurface");
    VkBool32 supported = VK_FALSE;
    sol::vk::check(vkGetPhysicalDeviceSurfaceSupportKHR(context.physical_device(), context.queue_family_index(), surface, &supported),
                   "vkGetPhysicalDeviceSurfaceSupportKHR");
    if (!supported) throw std::runtime_error("the Vulkan device '" + context.device_name() + "' cannot present to this window");
    VkFormatProperties props{};
    vkGetPhysicalDeviceFormatProperties(context.physical_device(), VK_FORMAT_R32G32B32A32_SFLOAT, &props);
    if (!(props.optimalTilingFeatures & VK_FORMAT_FEATURE_BLIT_SRC_BIT)) {
      throw std::runtime_error("the Vulkan device cannot blit from RGBA32F images");
    }
    linear_blit = (props.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT) != 0;
    VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO, nullptr,
                                      VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT, context.queue_family_index()};
    sol::vk::check(vkCreateCommandPool(device, &pool_info, nullptr, &pool), "vkCreateCommandPool");
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, nullptr, pool,
                                      VK_COMMAND_BUFFER_LEVEL_PRIMARY, 1};
    sol::vk::check(vkAllocateCommandBuffers(device, &alloc, &commands), "vkAllocateCommandBuffers");
    VkSemaphoreCreateInfo sem{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO, nullptr, 0};
    sol::vk::check(vkCreateSemaphore(device, &sem, nullptr, &acquired), "vkCreateSemaphore");
    // Signalled: the first frame's wait returns at once.
    VkFenceCreateInfo fence{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO, nullptr, VK_FENCE_CREATE_SIGNALED_BIT};
    sol::vk::check(vkCreateFence(device, &fence, nullptr, &frame_done), "vkCreateFence");
    create_swapchain(window, vsync);
  }

  void create_swapchain(GLFWwindow* window, bool vsync) {
    VkPhysicalDevice gpu = context.physical_device();
    VkDevice device = context.device();
    VkSurfaceCapabilitiesKHR caps{};
    sol::vk::check(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(gpu, surface, &caps), "vkGetPhysicalDeviceSurfaceCapabilitiesKHR");
    if (!(caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT)) {
      throw std::runtime_error("the surface's images cannot be blitted to (no TRANSFER_DST usage)");
    }
    std::uint32_t n = 0;
    vkGetPhysicalDeviceSurfaceFormatsKHR(gpu, surface, &n, nullptr);
    std::vector<VkSurfaceFormatKHR> formats(n);
    vkGetPhysicalDeviceSurfaceFormatsKHR(gpu, surface, &n, formats.data());
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
    direct_capable = false;
    for (const VkSurfaceFormatKHR& f : formats) {
      if ((caps.supportedUsageFlags & direct_usage) == direct_usage &&
          f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR && sol::vk::MarchRenderer::can_write_unorm(context, f.format)) {
        direct_capable = true;
        if (prefer_direct) chosen = f;
        break;
      }
    }
    direct = direct_capable && prefer_direct;
    format = chosen.format;
    vkGetPhysicalDeviceSurfacePresentModesKHR(gpu, surface, &n, nullptr);
    std::vector<VkPresentModeKHR> modes(n);
    vkGetPhysicalDeviceSurfacePresentModesKHR(gpu, surface, &n, modes.data());
    VkPresentModeKHR mode = VK_PRESENT_MODE_FIFO_KHR;  // always there: vsync
    if (!vsync) {
      for (VkPresentModeKHR m : {VK_PRESENT_MODE_MAILBOX_KHR, VK_PRESENT_MODE_IMMEDIATE_KHR}) {
        if (std::find(modes.begin(), modes.end(), m) != modes.end()) mode = m;
      }
    }
    extent = caps.currentExtent;
    if (extent.width == 0xFFFFFFFFu) {
      int w = 0, h = 0;
      glfwGetFramebufferSize(window, &w, &h);
      extent.width = std::clamp(static_cast<std::uint32_t>(w), caps.minImageExtent.width, caps.maxImageExtent.width);
      extent.height = std::clamp(static_cast<std::uint32_t>(h), caps.minImageExtent.height, caps.maxImageExtent.height);
    }
    if (extent.width == 0 || extent.height == 0) {  // minimised: no swapchain until it has a size
      destroy_swapchain();
      return;
    }
    std::uint32_t count = std::max(caps.minImageCount, 2u);
    if (caps.maxImageCount) count = std::min(count, caps.maxImageCount);
    VkSwapchainCreateInfoKHR info{};
    info.sType = VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR;
    info.surface = surface;
    info.minImageCount = count;
    info.imageFormat = chosen.format;
    info.imageColorSpace = chosen.colorSpace;
    info.imageExtent = extent;
    info.imageArrayLayers = 1;
    can_capture = (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT) != 0;
    info.imageUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                      (can_capture ? VkImageUsageFlags{VK_IMAGE_USAGE_TRANSFER_SRC_BIT} : VkImageUsageFlags{0}) |
                      (direct ? VkImageUsageFlags{VK_IMAGE_USAGE_STORAGE_BIT} : VkImageUsageFlags{0});
    info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.preTransform = caps.currentTransform;
    info.compositeAlpha = (caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR)
                              ? VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR
                              : static_cast<VkCompositeAlphaFlagBitsKHR>(caps.supportedCompositeAlpha & -caps.supportedCompositeAlpha);
    info.presentMode = mode;
    info.clipped = VK_TRUE;
    info.oldSwapchain = swapchain;
    VkSwapchainKHR created = VK_NULL_HANDLE;
    sol::vk::check(vkCreateSwapchainKHR(device, &info, nullptr, &created), "vkCreateSwapchainKHR");
    destroy_swapchain();
    swapchain = created;
    vkGetSwapchainImagesKHR(device, swapchain, &n, nullptr);
    images.resize(n);
    vkGetSwapchainImagesKHR(device, swapchain, &n, images.data());
    if (direct) {
      views.resize(n, VK_NULL_HANDLE);
      for (std::uint32_t i = 0; i < n; ++i) {
        VkImageViewCreateInfo view{};
        view.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
        view.image = images[i];
        view.viewType = VK_IMAGE_VIEW_TYPE_2D;
        view.format = format;
        view.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        sol::vk::check(vkCreateImageView(device, &view, nullptr, &views[i]), "vkCreateImageView");
      }
    }
    VkSemaphoreCreateInfo sem{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO, nullptr, 0};
    rendered.resize(n);
    for (VkSemaphore& s : rendered) sol::vk::check(vkCreateSemaphore(device, &sem, nullptr, &s), "vkCreateSemaphore");
  }

  // A host-visible buffer for one swapchain image (4 bytes per pixel).
  void ensure_capture_buffer() {
    const VkDeviceSize size = VkDeviceSize{extent.width} * extent.height * 4;
    if (capture != VK_NULL_HANDLE && capture_size == size) return;
    destroy_capture_buffer();
    VkDevice device = context.device();
    VkBufferCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
    info.size = size;
    info.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    sol::vk::check(vkCreateBuffer(device, &info, nullptr, &capture), "vkCreateBuffer");
    VkMemoryRequirements req{};
    vkGetBufferMemoryRequirements(device, capture, &req);
    VkPhysicalDeviceMemoryProperties mem{};
    vkGetPhysicalDeviceMemoryProperties(context.physical_device(), &mem);
    const VkMemoryPropertyFlags want = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    std::uint32_t type = mem.memoryTypeCount;
    for (std::uint32_t i = 0; i < mem.memoryTypeCount; ++i) {
      if ((req.memoryTypeBits & (1u << i)) && (mem.memoryTypes[i].propertyFlags & want) == want) {
        type = i;
        break;
      }
    }
    if (type == mem.memoryTypeCount) throw std::runtime_error("no host-visible memory for screenshots");
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, nullptr, req.size, type};
    sol::vk::check(vkAllocateMemory(device, &alloc, nullptr, &capture_memory), "vkAllocateMemory");
    sol::vk::check(vkBindBufferMemory(device, capture, capture_memory, 0), "vkBindBufferMemory");
    sol::vk::check(vkMapMemory(device, capture_memory, 0, VK_WHOLE_SIZE, 0, &capture_data), "vkMapMemory");
    capture_size = size;
  }
  void destroy_capture_buffer() {
    VkDevice device = context.device();
    if (capture_memory) vkFreeMemory(device, capture_memory, nullptr);  // unmaps
    if (capture) vkDestroyBuffer(device, capture, nullptr);
    capture = VK_NULL_HANDLE;
    capture_memory = VK_NULL_HANDLE;
    capture_data = nullptr;
    capture_size = 0;
  }
  // Writes the captured frame (extent as at capture) as 8-bit sRGB like solrender's PNGs.
  void write_capture(const std::string& path, std::uint32_t w, std::uint32_t h) const {
    const auto* bytes = static_cast<const unsigned char*>(capture_data);
    const bool bgr = format == VK_FORMAT_B8G8R8A8_SRGB || format == VK_FORMAT_B8G8R8A8_UNORM;
    const bool srgb = format == VK_FORMAT_B8G8R8A8_SRGB || format == VK_FORMAT_R8G8B8A8_SRGB || direct;
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
    sol::viewer::write_image(path, static_cast<int>(w), static_cast<int>(h), {"R", "G", "B", "A"}, rgba, !srgb);
  }

  void destroy_swapchain() {
    VkDevice device = context.device();
    for (VkSemaphore s : rendered) vkDestroySemaphore(device, s, nullptr);
    rendered.clear();
    for (VkImageView v : views) vkDestroyImageView(device, v, nullptr);
    views.clear();
    if (swapchain != VK_NULL_HANDLE) vkDestroySwapchainKHR(device, swapchain, nullptr);
    swapchain = VK_NULL_HANDLE;
    images.clear();
  }

  void recreate(GLFWwindow* window, bool vsync) {
    vkDeviceWaitIdle(context.device());  // nothing in flight may use the old images
    // The acquire semaphore may be left signalled by an acquire whose frame was dropped: a fresh one.
    VkDevice device = context.device();
    vkDestroySemaphore(device, acquired, nullptr);
    VkSemaphoreCreateInfo sem{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO, nullptr, 0};
    sol::vk::check(vkCreateSemaphore(device, &sem, nullptr, &acquired), "vkCreateSemaphore");
    create_swapchain(window, vsync);
  }

  ~Presenter() {
    VkDevice device = context.device();
    vkDeviceWaitIdle(device);
    destroy_swapchain();
    if (acquired) vkDestroySemaphore(device, acquired, nullptr);
    if (frame_done) vkDestroyFence(device, frame_done, nullptr);
    destroy_capture_buffer();
    if (pool) vkDestroyCommandPool(device, pool, nullptr);
    if (surface) vkDestroySurfaceKHR(context.instance(), surface, nullptr);
  }
};

std::string frame_name(const std::string& dir, long frame) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "frame-%06ld.png", frame);
  return (std::filesystem::path(dir) / buf).string();
}

void write_frame(const std::string& path, const sol::vk::StorageImage& image, int width, int height) {
  const std::vector<float> all = image.download();
  std::vector<float> rgba(static_cast<std::size_t>(width) * height * 4);
  for (int j = 0; j < height; ++j) {
    std::copy_n(all.begin() + static_cast<std::ptrdiff_t>(j) * image.width() * 4, width * 4,
                rgba.begin() + static_cast<std::ptrdiff_t>(j) * width * 4);
  }
  sol::viewer::write_image(path, width, height, {"R", "G", "B", "A"}, rgba, true);
}

void write_state(const std::string& path, const sol::Observer& o, long frames) {
  const std::string tmp = path + ".tmp";
  {
    std::FILE* f = std::fopen(tmp.c_str(), "w");
    if (!f) throw std::runtime_error(path + ": cannot write the state file");
    auto row = [&](const char* name, const glm::dvec3& v) { std::fprintf(f, "%s %.17g %.17g %.17g\n", name, v.x, v.y, v.z); };
    row("position", o.position());
    row("forward", o.forward());
    row("up", o.up());
    std::fprintf(f, "frames %ld\n", frames);
    if (std::fclose(f) != 0) throw std::runtime_error(path + ": cannot write the state file");
  }
  std::filesystem::rename(tmp, path);
}

int run(App& app) {
  Options& opt = app.options;
  std::vector<sol::viewer::ScriptEvent> script;
  if (!opt.script.empty()) {
    try {
      script = sol::viewer::load_script(opt.script);
    } catch (const std::exception& e) {
      fail(e.what());
    }
  }
  if (!opt.screenshot.empty() && !sol::viewer::can_write(opt.screenshot)) {
    fail("--screenshot " + opt.screenshot + ": no image format for this file name extension");
  }
  if (!opt.record.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(opt.record, ec);
    if (ec || !std::filesystem::is_directory(opt.record)) fail("--record " + opt.record + ": cannot create the directory");
  }

  glfwSetErrorCallback(on_glfw_error);
  if (!glfwInit()) {
    fail("cannot open a window: " + glfw_error + (std::getenv("DISPLAY") ? "" : " (DISPLAY is not set: run under a display or xvfb-run)"), 1);
  }
  struct GlfwGuard {
    ~GlfwGuard() { glfwTerminate(); }
  } glfw_guard;
  if (!glfwVulkanSupported()) fail("cannot open a window: GLFW finds no Vulkan loader", 1);

  sol::vk::ContextOptions context_options;
  context_options.validation = opt.validation;
  std::uint32_t n_ext = 0;
  const char** ext = glfwGetRequiredInstanceExtensions(&n_ext);
  if (!ext) fail("cannot open a window: GLFW cannot present Vulkan images here (" + glfw_error + ")", 1);
  for (std::uint32_t i = 0; i < n_ext; ++i) context_options.instance_extensions.emplace_back(ext[i]);
  context_options.device_extensions.emplace_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
  sol::vk::Context context(context_options);
  sol::vk::MarchRenderer renderer(context);

  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  GLFWwindow* window = glfwCreateWindow(opt.width, opt.height, "solview", nullptr, nullptr);
  if (!window) fail("cannot open a window: " + glfw_error, 1);
  struct WindowGuard {
    GLFWwindow* w;
    ~WindowGuard() { glfwDestroyWindow(w); }
  } window_guard{window};
  app.window = window;
  glfwSetWindowUserPointer(window, &app);
  if (opt.fullscreen) app.toggle_fullscreen();
  const bool replay = !opt.script.empty();
  // During a replay live input is ignored: the script alone moves the observer.
  if (!replay) {
    glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int, int action, int) {
      if (auto k = key_of(key); k && action != GLFW_REPEAT) app_of(w).key(*k, action == GLFW_PRESS);
    });
    glfwSetMouseButtonCallback(window, [](GLFWwindow* w, int button, int action, int) {
      if (button != GLFW_MOUSE_BUTTON_LEFT) return;
      App& a = app_of(w);
      a.dragging = action == GLFW_PRESS;
      glfwGetCursorPos(w, &a.last_x, &a.last_y);
    });
    glfwSetCursorPosCallback(window, [](GLFWwindow* w, double x, double y) {
      App& a = app_of(w);
      if (a.dragging) a.controls.mouse(x - a.last_x, y - a.last_y);
      a.last_x = x;
      a.last_y = y;
    });
  }
  glfwSetFramebufferSizeCallback(window, [](GLFWwindow* w, int, int) { app_of(w).swapchain_dirty = true; });

  Presenter present(context);
  present.prefer_direct = opt.allow_direct && app.scale == 1.0;
  present.init(window, app.vsync);
  VkDevice device = context.device();

  std::optional<sol::vk::StorageImage> target;  // the kernel's output at the render scale
  int render_w = 0, render_h = 0;  // of the rendered image (both eyes)
  bool target_has_frame = false;   // the target holds the last frame shown (for --screenshot at exit)
  std::uint32_t captured_w = 0, captured_h = 0;  // of the frame in the capture buffer (0: none)
  // Saves the last frame: as shown (the swapchain image) when the surface lets
  // it be copied, else as rendered (before upscaling).
  auto save = [&](const std::string& path) {
    if (captured_w != 0) {
      present.write_capture(path, captured_w, captured_h);
    } else {
      write_frame(path, *target, render_w, render_h);
    }
  };
  std::size_t next_event = 0;
  long frame = 0;
  double smoothed_ms = 0;
  auto last = std::chrono::steady_clock::now();
  auto title_time = last;
  long title_frames = 0;
  double fps = 0;
  constexpr long kWarmupFrames = 5;
  auto measure_start = std::chrono::steady_clock::now();
  double scale_sum = 0;  // over the measured frames
  double host_ms_sum = 0;  // host time to prepare and record a frame, over the measured frames
  long direct_frames = 0, blit_frames = 0;
  int shown_w = 0, shown_h = 0;  // of the last frame's rendered image (both eyes)
  const long first_measured = std::max(kWarmupFrames, opt.frames / 2) + 1;

  while (!glfwWindowShouldClose(window) && !app.quit && (opt.frames == 0 || frame < opt.frames)) {
    glfwPollEvents();
    if (app.swapchain_dirty || present.swapchain == VK_NULL_HANDLE) {
      app.swapchain_dirty = false;
      present.recreate(window, app.vsync);
      if (present.swapchain == VK_NULL_HANDLE) {  // minimised
        glfwWaitEvents();
        continue;
      }
    }
    // Input: a replay steps fixed 1/60 s per frame (deterministic), live input by the clock.
    const auto now = std::chrono::steady_clock::now();
    const double frame_seconds = std::chrono::duration<double>(now - last).count();
    last = now;
    double dt = std::min(frame_seconds, 0.1);
    if (replay) {
      dt = sol::viewer::kScriptStep;
      const double t = static_cast<double>(frame) * sol::viewer::kScriptStep;
      for (; next_event < script.size() && script[next_event].time <= t + 1e-9; ++next_event) {
        const auto& e = script[next_event];
        if (e.kind == sol::viewer::ScriptEvent::Kind::Mouse) {
          app.controls.mouse(e.dx, e.dy);
        } else {
          app.key(e.key, e.kind == sol::viewer::ScriptEvent::Kind::Down);
        }
      }
    }
    if (app.quit) break;
    app.controls.step(app.observer, dt);

    // Adaptive scale: the frame time goes with the pixel count, scale².
    if (frame > 0) smoothed_ms = smoothed_ms == 0 ? frame_seconds * 1e3 : 0.8 * smoothed_ms + 0.2 * frame_seconds * 1e3;
    // Every 8 frames, or at once when a frame took over twice the target time
    // (a slow scene must not crawl through 8 full-size frames first).
    const bool far_too_slow = opt.target_fps && frame > 1 && frame_seconds * *opt.target_fps > 2.0;
    if (far_too_slow) smoothed_ms = frame_seconds * 1e3;
    if (app.adaptive && opt.target_fps && (frame % 8 == 0 || far_too_slow) && smoothed_ms > 0) {
      // Aim 10% above the target so that the dead band below never leaves the rate under it.
      const double wanted = app.scale * std::sqrt(1e3 / (1.1 * *opt.target_fps) / smoothed_ms);
      const double next = std::clamp(wanted, opt.min_scale, 1.0);
      // A 5% dead band against dithering; the bounds are taken whatever the
      // step (scale 1 is the direct path, see Presenter; at 0.97 it would
      // never be reached).
      const bool at_bound = next == opt.min_scale || next == 1.0;
      if (std::abs(next - app.scale) > 0.05 * app.scale || (at_bound && next != app.scale)) app.scale = next;
    }

    const int eyes = app.stereo ? 2 : 1;
    int eye_w = 0, eye_h = 0;
    auto fits_window = [&] {  // the rendered image covers the swapchain image exactly
      eye_w = std::max(1, static_cast<int>(std::lround(present.extent.width * app.scale / eyes)));
      eye_h = std::max(1, static_cast<int>(std::lround(present.extent.height * app.scale)));
      return static_cast<std::uint32_t>(eye_w * eyes) == present.extent.width &&
             static_cast<std::uint32_t>(eye_h) == present.extent.height;
    };
    // The path: direct when the kernel renders at the window's size and the
    // surface allows it; a change of path re-creates the swapchain (UNORM
    // with STORAGE usage for the direct path, sRGB for the blit).
    const bool fits = fits_window();  // sets eye_w, eye_h
    present.prefer_direct = opt.allow_direct && fits;
    if (present.direct_capable && present.direct != present.prefer_direct) {
      present.recreate(window, app.vsync);
      if (present.swapchain == VK_NULL_HANDLE) continue;  // minimised meanwhile: the top of the loop waits
    }
    if (present.direct && !fits_window()) {  // the window changed size meanwhile
      app.swapchain_dirty = true;
      continue;
    }
    const bool direct = present.direct;

    // One frame in flight: wait until the previous frame's commands are done
    // before touching its command buffer, the renderer's uniforms or the target.
    sol::vk::check(vkWaitForFences(device, 1, &present.frame_done, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    if (!direct && (!target || render_w != eye_w * eyes || render_h != eye_h)) {
      target.reset();
      target.emplace(context, static_cast<std::uint32_t>(eye_w * eyes), static_cast<std::uint32_t>(eye_h));
      render_w = eye_w * eyes;
      render_h = eye_h;
      target_has_frame = false;
    }
    std::uint32_t index = 0;
    VkResult acquired = vkAcquireNextImageKHR(device, present.swapchain, UINT64_MAX, present.acquired, VK_NULL_HANDLE, &index);
    if (acquired == VK_ERROR_OUT_OF_DATE_KHR) {
      app.swapchain_dirty = true;
      continue;
    }
    if (acquired != VK_SUBOPTIMAL_KHR) sol::vk::check(acquired, "vkAcquireNextImageKHR");
    sol::vk::check(vkResetFences(device, 1, &present.frame_done), "vkResetFences");

    const auto host_begin = std::chrono::steady_clock::now();
    // The world is prepared once per scene (the previous frame is done: the fence above).
    if (app.world_changed) {
      renderer.set_world(app.scene);
      app.world_changed = false;
    }
    // Per frame only the cameras change.
    sol::Camera camera = app.scene.camera;
    camera.position = app.observer.position();
    camera.forward = app.observer.forward();
    camera.up = app.observer.up();
    std::vector<sol::Camera> cameras;
    if (app.stereo) {
      const sol::StereoEyes se = sol::stereo_eyes(camera, opt.ipd);
      cameras = {se.left, se.right};
    } else {
      cameras = {camera};
    }

    VkCommandBuffer cb = present.commands;
    sol::vk::check(vkResetCommandBuffer(cb, 0), "vkResetCommandBuffer");
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO, nullptr,
                                   VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT, nullptr};
    sol::vk::check(vkBeginCommandBuffer(cb, &begin), "vkBeginCommandBuffer");
    VkImage swap_image = present.images[index];
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
      sol::vk::image_barrier(cb, swap_image, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                    VK_ACCESS_SHADER_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
      renderer.record(cb, cameras, eye_w, eye_h,
                      sol::vk::UnormTarget{present.views[index], present.format, present.extent.width, present.extent.height});
      shown_layout = VK_IMAGE_LAYOUT_GENERAL;
      shown_stage = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
      shown_access = VK_ACCESS_SHADER_WRITE_BIT;
    } else {
      VkImage target_image = target->handle();
      renderer.record(cb, cameras, eye_w, eye_h, *target);
      // Read after write: the blit reads what the kernel wrote; to the layout
      // blits read best (the previous frame's last barrier already ordered this
      // frame's kernel after that frame's blit).
      sol::vk::image_barrier(cb, target_image, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                    VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT, VK_IMAGE_LAYOUT_GENERAL,
                    VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
      // The swapchain image: its old contents are not needed (UNDEFINED); the
      // transition waits at the transfer stage, the stage the submit's wait on
      // `acquired` blocks, so it happens only after the presentation engine
      // has released the image.
      sol::vk::image_barrier(cb, swap_image, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT,
                    VK_ACCESS_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
      VkImageBlit blit{};
      blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
      blit.srcOffsets[1] = {render_w, render_h, 1};
      blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
      blit.dstOffsets[1] = {static_cast<std::int32_t>(present.extent.width), static_cast<std::int32_t>(present.extent.height), 1};
      const bool same_size = static_cast<std::uint32_t>(render_w) == present.extent.width &&
                             static_cast<std::uint32_t>(render_h) == present.extent.height;
      vkCmdBlitImage(cb, target_image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, swap_image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit,
                     same_size || !present.linear_blit ? VK_FILTER_NEAREST : VK_FILTER_LINEAR);
      // Back to GENERAL, where Sol::vk expects its storage images between
      // commands (the next kernel, download()); write after read: the next
      // frame's kernel and any download's copy wait for the blit to finish reading.
      sol::vk::image_barrier(cb, target_image, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT,
                    VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                    VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_READ_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                    VK_IMAGE_LAYOUT_GENERAL);
    }
    // Screenshots and --record take the frame as shown: the swapchain image
    // after the blit, copied to a host-visible buffer.
    const bool capturing = present.can_capture && (!opt.record.empty() || !opt.screenshot.empty() || app.want_screenshot);
    if (capturing) {
      present.ensure_capture_buffer();
      // Read after write: the copy reads what the blit or the kernel wrote.
      sol::vk::image_barrier(cb, swap_image, shown_stage, shown_access, VK_PIPELINE_STAGE_TRANSFER_BIT,
                    VK_ACCESS_TRANSFER_READ_BIT, shown_layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
      VkBufferImageCopy copy{};
      copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
      copy.imageExtent = {present.extent.width, present.extent.height, 1};
      vkCmdCopyImageToBuffer(cb, swap_image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, present.capture, 1, &copy);
      // The host reads the buffer after the fence: make the copy's writes visible to it.
      VkBufferMemoryBarrier host{};
      host.sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER;
      host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
      host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
      host.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
      host.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
      host.buffer = present.capture;
      host.size = VK_WHOLE_SIZE;
      vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0, nullptr, 1, &host, 0,
                           nullptr);
      shown_layout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
      shown_stage = VK_PIPELINE_STAGE_TRANSFER_BIT;
      shown_access = VK_ACCESS_TRANSFER_READ_BIT;
    }
    // To the presentation layout; the present waits on `rendered`, which the
    // submit signals after all these commands, so no later stage needs to wait here.
    sol::vk::image_barrier(cb, swap_image, shown_stage, shown_access, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 0, shown_layout,
                  VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);
    sol::vk::check(vkEndCommandBuffer(cb), "vkEndCommandBuffer");
    const double host_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - host_begin).count();

    // The first use of the swapchain image waits for the acquire: the kernel
    // on the direct path; the blit otherwise (the kernel may run before the image is free).
    const VkPipelineStageFlags wait_stage = direct ? VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT : VK_PIPELINE_STAGE_TRANSFER_BIT;
    VkSubmitInfo submit{};
    submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    submit.waitSemaphoreCount = 1;
    submit.pWaitSemaphores = &present.acquired;
    submit.pWaitDstStageMask = &wait_stage;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cb;
    submit.signalSemaphoreCount = 1;
    submit.pSignalSemaphores = &present.rendered[index];
    sol::vk::check(vkQueueSubmit(context.queue(), 1, &submit, present.frame_done), "vkQueueSubmit");
    VkPresentInfoKHR info{};
    info.sType = VK_STRUCTURE_TYPE_PRESENT_INFO_KHR;
    info.waitSemaphoreCount = 1;
    info.pWaitSemaphores = &present.rendered[index];
    info.swapchainCount = 1;
    info.pSwapchains = &present.swapchain;
    info.pImageIndices = &index;
    const VkResult presented = vkQueuePresentKHR(context.queue(), &info);
    if (presented == VK_ERROR_OUT_OF_DATE_KHR || presented == VK_SUBOPTIMAL_KHR) {
      app.swapchain_dirty = true;
    } else {
      sol::vk::check(presented, "vkQueuePresentKHR");
    }
    ++frame;
    target_has_frame = !direct;
    ++(direct ? direct_frames : blit_frames);
    shown_w = eye_w * eyes;
    shown_h = eye_h;
    // The run's mean frame rate leaves out the first frames (pipeline builds, first allocations).
    // With --frames, the second half only: the adaptive scale has settled by then.
    if (frame == first_measured - 1) measure_start = std::chrono::steady_clock::now();

    if (capturing) {
      captured_w = present.extent.width;
      captured_h = present.extent.height;
    }
    if (!opt.record.empty() || app.want_screenshot) {
      // The frame's commands must be done before the host reads the capture or the target.
      sol::vk::check(vkWaitForFences(device, 1, &present.frame_done, VK_TRUE, UINT64_MAX), "vkWaitForFences");
      if (!opt.record.empty()) save(frame_name(opt.record, frame - 1));
      if (app.want_screenshot) {
        app.want_screenshot = false;
        char name[32];
        std::snprintf(name, sizeof name, "solview-%04d.png", app.screenshots++);
        save(name);
        std::printf("solview: screenshot %s\n", name);
      }
    }

    if (frame >= first_measured) {
      scale_sum += app.scale;
      host_ms_sum += host_ms;
    }
    ++title_frames;
    const double since = std::chrono::duration<double>(std::chrono::steady_clock::now() - title_time).count();
    if (since >= 0.5) {
      fps = static_cast<double>(title_frames) / since;
      title_frames = 0;
      title_time = std::chrono::steady_clock::now();
      const glm::dvec3 p = app.observer.position();
      char title[256];
      std::snprintf(title, sizeof title, "solview - %s - %.1f fps - scale %.2f%s - (%.3f, %.3f, %.3f) - H: help",
                    app.scene_name.c_str(), fps, app.scale, app.adaptive ? " (adaptive)" : "", p.x, p.y, p.z);
      glfwSetWindowTitle(window, title);
    }
  }
  vkDeviceWaitIdle(device);
  // --screenshot: the last frame shown, however the run ended (--frames, Esc, closing the window).
  if (!opt.screenshot.empty()) {
    if (captured_w == 0 && (!target || !target_has_frame)) {
      throw std::runtime_error("--screenshot " + opt.screenshot + ": no frame was rendered");
    }
    save(opt.screenshot);
  }
  target.reset();
  if (!opt.state.empty()) write_state(opt.state, app.observer, frame);
  const long measured = frame - first_measured + 1;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - measure_start).count();
  if (measured > 0) {
    std::fprintf(stderr, "solview: %s: %.2f fps (mean over frames %ld..%ld), mean render scale %.2f\n",
                 app.scene_name.c_str(), static_cast<double>(measured) / seconds, first_measured, frame,
                 scale_sum / static_cast<double>(measured));
    // The host's share of a frame: the scene and cameras, the renderer's
    // preparation and the recorded commands (no waits on the device).
    std::fprintf(stderr, "solview: host %.3f ms per frame to prepare and record (mean over frames %ld..%ld)\n",
                 host_ms_sum / static_cast<double>(measured), first_measured, frame);
  }
  std::fprintf(stderr, "solview: %ld frames, render scale %.2f at the end (%dx%d of %ux%u)\n", frame, app.scale,
               shown_w, shown_h, present.extent.width, present.extent.height);
  // Which path presented the frames (viewer/README.md: How solview presents a frame).
  std::fprintf(stderr, "solview: present: direct %ld frames, blit %ld frames (direct path %s)\n", direct_frames,
               blit_frames, present.direct_capable ? "available" : "unavailable on this surface");
  if (context.validation_enabled()) {
    const std::vector<std::string> errors = context.validation_errors();
    for (const std::string& e : errors) std::fprintf(stderr, "solview: validation: %s\n", e.c_str());
    if (!errors.empty()) return 3;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  App app;
  app.options = parse_options(argc, argv);
  try {
    app.set_scene(app.options.scene);
  } catch (const std::exception& e) {
    fail(e.what());
  }
  app.scale = app.options.scale;
  app.adaptive = app.options.target_fps.has_value();
  app.stereo = app.options.stereo;
  app.vsync = app.options.vsync;
  try {
    return run(app);
  } catch (const std::exception& e) {
    fail(e.what(), 4);
  }
}
