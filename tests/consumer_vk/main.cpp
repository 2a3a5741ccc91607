// A Vulkan application that draws Sol's frame with its own device, queue,
// command buffer, image and fence, using only the installed Sol::vk; and
// the headless path beside it. docs/libsol.md walks through it.
//
//   consumer_vk SCENE WIDTH HEIGHT OUT.pfm OUT.ppm
//
// OUT.pfm: the headless path (a Context of Sol's own, render() read back):
// linear RGB floats, rows bottom to top. OUT.ppm: the application's path
// (its VkDevice adopted by sol::vk::Context, the frame recorded into its
// command buffer, written into its 8-bit UNORM storage image, sRGB-encoded
// by the kernel, copied to its buffer): 8-bit sRGB RGB, rows top to bottom.
// The test compares both with solrender's images.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <sol/sol.hpp>
#include <sol/vk/context.hpp>
#include <sol/vk/march.hpp>
#include <vulkan/vulkan.h>

namespace {

void check(VkResult result, const char* what) {
  if (result != VK_SUCCESS) throw std::runtime_error(std::string(what) + " failed: VkResult " + std::to_string(result));
}

// ---- The application's own Vulkan objects (what any engine already has) ----

struct App {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  std::uint32_t family = 0;
  VkQueue queue = VK_NULL_HANDLE;
  bool write_without_format = false;

  App() {
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "consumer_vk";
    app.apiVersion = VK_API_VERSION_1_2;  // Sol needs 1.2
    VkInstanceCreateInfo instance_info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    instance_info.pApplicationInfo = &app;
    check(vkCreateInstance(&instance_info, nullptr, &instance), "vkCreateInstance");
    std::uint32_t count = 0;
    vkEnumeratePhysicalDevices(instance, &count, nullptr);
    std::vector<VkPhysicalDevice> devices(count);
    vkEnumeratePhysicalDevices(instance, &count, devices.data());
    for (VkPhysicalDevice d : devices) {  // the first device with a queue that computes (and draws)
      std::uint32_t n = 0;
      vkGetPhysicalDeviceQueueFamilyProperties(d, &n, nullptr);
      std::vector<VkQueueFamilyProperties> families(n);
      vkGetPhysicalDeviceQueueFamilyProperties(d, &n, families.data());
      for (std::uint32_t i = 0; i < n && physical == VK_NULL_HANDLE; ++i) {
        if ((families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) != 0) {
          physical = d;
          family = i;
        }
      }
      if (physical != VK_NULL_HANDLE) break;
    }
    if (physical == VK_NULL_HANDLE) throw std::runtime_error("no Vulkan device with a compute queue");
    // The one feature Sol's 8-bit output needs: storage writes to images
    // declared without a format (UNORM swapchain-style images).
    VkPhysicalDeviceFeatures supported{};
    vkGetPhysicalDeviceFeatures(physical, &supported);
    VkPhysicalDeviceFeatures enabled{};
    enabled.shaderStorageImageWriteWithoutFormat = supported.shaderStorageImageWriteWithoutFormat;
    write_without_format = supported.shaderStorageImageWriteWithoutFormat == VK_TRUE;
    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queue_info.queueFamilyIndex = family;
    queue_info.queueCount = 1;
    queue_info.pQueuePriorities = &priority;
    VkDeviceCreateInfo device_info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    device_info.queueCreateInfoCount = 1;
    device_info.pQueueCreateInfos = &queue_info;
    device_info.pEnabledFeatures = &enabled;
    check(vkCreateDevice(physical, &device_info, nullptr, &device), "vkCreateDevice");
    vkGetDeviceQueue(device, family, 0, &queue);
  }
  ~App() {
    vkDestroyDevice(device, nullptr);
    vkDestroyInstance(instance, nullptr);
  }
  App(const App&) = delete;
  App& operator=(const App&) = delete;

  // Memory of a type with `flags` for what `needs` describes.
  VkDeviceMemory allocate(const VkMemoryRequirements& needs, VkMemoryPropertyFlags flags) const {
    VkPhysicalDeviceMemoryProperties memory{};
    vkGetPhysicalDeviceMemoryProperties(physical, &memory);
    VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    info.allocationSize = needs.size;
    info.memoryTypeIndex = memory.memoryTypeCount;
    for (std::uint32_t i = 0; i < memory.memoryTypeCount && info.memoryTypeIndex == memory.memoryTypeCount; ++i) {
      if ((needs.memoryTypeBits & (1u << i)) != 0 && (memory.memoryTypes[i].propertyFlags & flags) == flags) info.memoryTypeIndex = i;
    }
    if (info.memoryTypeIndex == memory.memoryTypeCount) throw std::runtime_error("no suitable memory type");
    VkDeviceMemory out = VK_NULL_HANDLE;
    check(vkAllocateMemory(device, &info, nullptr, &out), "vkAllocateMemory");
    return out;
  }
};

// The application's frame: Sol draws into its image in its command buffer.
std::vector<std::uint8_t> app_frame(App& app, sol::vk::MarchRenderer& renderer, const sol::Camera& camera, int width,
                                    int height) {
  const auto w = static_cast<std::uint32_t>(width), h = static_cast<std::uint32_t>(height);
  const VkFormat format = VK_FORMAT_R8G8B8A8_UNORM;
  // Its image (STORAGE for Sol's kernel, TRANSFER_SRC to read it here; a
  // real application would present or sample it) and a host buffer.
  VkImageCreateInfo image_info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  image_info.imageType = VK_IMAGE_TYPE_2D;
  image_info.format = format;
  image_info.extent = {w, h, 1};
  image_info.mipLevels = 1;
  image_info.arrayLayers = 1;
  image_info.samples = VK_SAMPLE_COUNT_1_BIT;
  image_info.tiling = VK_IMAGE_TILING_OPTIMAL;
  image_info.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  VkImage image = VK_NULL_HANDLE;
  check(vkCreateImage(app.device, &image_info, nullptr, &image), "vkCreateImage");
  VkMemoryRequirements image_needs{};
  vkGetImageMemoryRequirements(app.device, image, &image_needs);
  const VkDeviceMemory image_memory = app.allocate(image_needs, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  check(vkBindImageMemory(app.device, image, image_memory, 0), "vkBindImageMemory");
  VkImageViewCreateInfo view_info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  view_info.image = image;
  view_info.viewType = VK_IMAGE_VIEW_TYPE_2D;
  view_info.format = format;
  view_info.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  VkImageView view = VK_NULL_HANDLE;
  check(vkCreateImageView(app.device, &view_info, nullptr, &view), "vkCreateImageView");
  VkBufferCreateInfo buffer_info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  buffer_info.size = VkDeviceSize{4} * w * h;
  buffer_info.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  VkBuffer buffer = VK_NULL_HANDLE;
  check(vkCreateBuffer(app.device, &buffer_info, nullptr, &buffer), "vkCreateBuffer");
  VkMemoryRequirements buffer_needs{};
  vkGetBufferMemoryRequirements(app.device, buffer, &buffer_needs);
  const VkDeviceMemory buffer_memory =
      app.allocate(buffer_needs, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  check(vkBindBufferMemory(app.device, buffer, buffer_memory, 0), "vkBindBufferMemory");

  // Its command buffer: the image into GENERAL, Sol's frame, then the copy.
  VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pool_info.queueFamilyIndex = app.family;
  VkCommandPool pool = VK_NULL_HANDLE;
  check(vkCreateCommandPool(app.device, &pool_info, nullptr, &pool), "vkCreateCommandPool");
  VkCommandBufferAllocateInfo command_info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  command_info.commandPool = pool;
  command_info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  command_info.commandBufferCount = 1;
  VkCommandBuffer commands = VK_NULL_HANDLE;
  check(vkAllocateCommandBuffers(app.device, &command_info, &commands), "vkAllocateCommandBuffers");
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(vkBeginCommandBuffer(commands, &begin), "vkBeginCommandBuffer");
  VkImageMemoryBarrier to_general{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  to_general.dstAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  to_general.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  to_general.newLayout = VK_IMAGE_LAYOUT_GENERAL;
  to_general.srcQueueFamilyIndex = to_general.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  to_general.image = image;
  to_general.subresourceRange = view_info.subresourceRange;
  vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0, nullptr, 0,
                       nullptr, 1, &to_general);
  // Sol's frame: its dispatches (and the barriers between its passes).
  renderer.record(commands, std::span(&camera, 1), width, height, sol::vk::UnormTarget{view, format, w, h});
  VkImageMemoryBarrier to_copy = to_general;
  to_copy.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  to_copy.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
  to_copy.oldLayout = VK_IMAGE_LAYOUT_GENERAL;
  to_copy.newLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0,
                       nullptr, 1, &to_copy);
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {w, h, 1};
  vkCmdCopyImageToBuffer(commands, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer, 1, &region);
  VkBufferMemoryBarrier to_host{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER};
  to_host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  to_host.srcQueueFamilyIndex = to_host.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  to_host.buffer = buffer;
  to_host.size = VK_WHOLE_SIZE;
  vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0, nullptr, 1, &to_host, 0,
                       nullptr);
  check(vkEndCommandBuffer(commands), "vkEndCommandBuffer");

  // Its submission and its fence.
  VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VkFence fence = VK_NULL_HANDLE;
  check(vkCreateFence(app.device, &fence_info, nullptr, &fence), "vkCreateFence");
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &commands;
  check(vkQueueSubmit(app.queue, 1, &submit, fence), "vkQueueSubmit");
  check(vkWaitForFences(app.device, 1, &fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");

  std::vector<std::uint8_t> rgba(static_cast<std::size_t>(buffer_info.size));
  void* mapped = nullptr;
  check(vkMapMemory(app.device, buffer_memory, 0, VK_WHOLE_SIZE, 0, &mapped), "vkMapMemory");
  std::memcpy(rgba.data(), mapped, rgba.size());
  vkUnmapMemory(app.device, buffer_memory);
  vkDestroyFence(app.device, fence, nullptr);
  vkDestroyCommandPool(app.device, pool, nullptr);
  vkDestroyBuffer(app.device, buffer, nullptr);
  vkFreeMemory(app.device, buffer_memory, nullptr);
  vkDestroyImageView(app.device, view, nullptr);
  vkDestroyImage(app.device, image, nullptr);
  vkFreeMemory(app.device, image_memory, nullptr);
  return rgba;
}

void write_pfm(const char* path, const sol::RenderResult& image) {
  std::FILE* out = std::fopen(path, "wb");
  if (!out) throw std::runtime_error(std::string("cannot write ") + path);
  std::fprintf(out, "PF\n%d %d\n-1.0\n", image.width, image.height);  // (a negative scale: little-endian floats)
  for (int y = image.height - 1; y >= 0; --y) {
    for (int x = 0; x < image.width; ++x) {
      std::fwrite(&image.rgba[4 * (static_cast<std::size_t>(y) * image.width + x)], sizeof(float), 3, out);
    }
  }
  if (std::fclose(out) != 0) throw std::runtime_error(std::string("cannot write ") + path);
}

void write_ppm(const char* path, const std::vector<std::uint8_t>& rgba, int width, int height) {
  std::FILE* out = std::fopen(path, "wb");
  if (!out) throw std::runtime_error(std::string("cannot write ") + path);
  std::fprintf(out, "P6\n%d %d\n255\n", width, height);
  for (std::size_t i = 0; i < rgba.size(); i += 4) std::fwrite(&rgba[i], 1, 3, out);
  if (std::fclose(out) != 0) throw std::runtime_error(std::string("cannot write ") + path);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 6) {
    std::fprintf(stderr, "usage: consumer_vk SCENE WIDTH HEIGHT OUT.pfm OUT.ppm\n");
    return 2;
  }
  try {
    const sol::Scene scene = sol::preset_scene(argv[1]);
    const int width = std::atoi(argv[2]), height = std::atoi(argv[3]);
    {
      // Headless: Sol's own context, the frame read back as floats.
      sol::vk::Context context;  // a GPU, else lavapipe (SOL_VK_DEVICE=gpu|cpu)
      sol::vk::MarchRenderer renderer(context);
      renderer.set_world(scene);  // once per world
      write_pfm(argv[4], renderer.render(scene.camera, {.width = width, .height = height}));
      std::printf("Sol::vk headless on %s: %s %dx%d -> %s\n", context.device_name().c_str(), argv[1], width, height, argv[4]);
    }
    {
      // In an application: its device adopted, the frame in its command buffer.
      App app;
      std::vector<std::uint8_t> rgba;
      {
        sol::vk::Context context(sol::vk::ExternalDevice{.instance = app.instance,
                                                         .physical_device = app.physical,
                                                         .device = app.device,
                                                         .queue_family = app.family,
                                                         .storage_write_without_format = app.write_without_format});
        if (!sol::vk::MarchRenderer::can_write_unorm(context, VK_FORMAT_R8G8B8A8_UNORM)) {
          throw std::runtime_error("the device cannot take Sol's 8-bit output (shaderStorageImageWriteWithoutFormat)");
        }
        sol::vk::MarchRenderer renderer(context);
        renderer.set_world(scene);
        rgba = app_frame(app, renderer, scene.camera, width, height);
        std::printf("Sol::vk in the application's device %s: %s %dx%d -> %s\n", context.device_name().c_str(), argv[1],
                    width, height, argv[5]);
      }  // Sol's objects go before the application destroys its device
      write_ppm(argv[5], rgba, width, height);
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "consumer_vk: %s\n", e.what());
    return 1;
  }
}
