#include "sol/vk/context.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <utility>

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <sol/file_io.hpp>

#include "device.hpp"
#include "sol/vk/error.hpp"

namespace sol::vk {
namespace {

// The pipeline cache file's bytes, or none (with a warning naming it) when
// it is not a regular file (a directory, a FIFO that would block, a link to
// a device such as /dev/zero that never ends), larger than any cache, or
// unreadable: a cache is optional and never stops a render.
std::vector<char> read_pipeline_cache(const std::string& path) {
  constexpr std::uintmax_t kLargest = std::uintmax_t{1} << 30;
  FileRefusal why;
  const std::optional<std::string> bytes = read_regular_file(path, kLargest, &why);
  if (!bytes) {
    using Kind = FileRefusal::Kind;
    const std::string problem = why.kind == Kind::Directory    ? "it is a directory"
                                : why.kind == Kind::NotRegular ? "it is not a regular file"
                                : why.kind == Kind::TooLarge   ? "it is larger than any pipeline cache (1 GiB)"
                                                               : why.text;
    if (why.kind != Kind::Missing) {
      std::fprintf(stderr, "sol::vk: warning: ignoring the pipeline cache %s: %s (the kernels are compiled again)\n",
                   path.c_str(), problem.c_str());
    }
    return {};
  }
  return std::vector<char>(bytes->begin(), bytes->end());
}

// Mesa's drivers keep a shader cache of their own under $XDG_CACHE_HOME
// (or ~/.cache) and write it through a memory map: on a full disk the
// process dies of SIGBUS with no message. Where that folder's file system
// has less than 64 MiB free, or cannot be written, the cache is turned off
// for this process (MESA_SHADER_CACHE_DISABLE; other drivers ignore it),
// with a note, unless the user chose a setting or a folder of their own.
void guard_driver_shader_cache() {
  if (std::getenv("MESA_SHADER_CACHE_DISABLE") || std::getenv("MESA_SHADER_CACHE_DIR") ||
      std::getenv("MESA_GLSL_CACHE_DISABLE") || std::getenv("MESA_GLSL_CACHE_DIR")) {
    return;
  }
  std::filesystem::path dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) {
    dir = xdg;
  } else if (const char* home = std::getenv("HOME"); home && *home) {
    dir = std::filesystem::path(home) / ".cache";
  } else {
    return;
  }
  // The nearest folder that exists: Mesa creates the rest.
  std::error_code ec;
  while (!dir.empty() && !std::filesystem::exists(dir, ec)) dir = dir.parent_path();
  if (dir.empty()) return;
  struct statvfs fs {};
  constexpr unsigned long long kLeast = 64ull << 20;
  const bool room = ::statvfs(dir.c_str(), &fs) == 0 &&
                    static_cast<unsigned long long>(fs.f_bavail) * fs.f_frsize >= kLeast && ::access(dir.c_str(), W_OK) == 0;
  if (room) return;
  ::setenv("MESA_SHADER_CACHE_DISABLE", "true", 0);
  std::fprintf(stderr, "sol::vk: note: %s has under 64 MiB free or cannot be written: the driver's shader cache is off\n",
               dir.c_str());
}

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

/// The two-call enumeration idiom, repeated while the list grows (VK_INCOMPLETE).
template <class T, class Enumerate>
std::vector<T> enumerate(const char* call, Enumerate&& enumerate_into) {
  std::vector<T> items;
  for (;;) {
    std::uint32_t count = 0;
    check(enumerate_into(&count, static_cast<T*>(nullptr)), call);
    items.resize(count);
    const VkResult result = enumerate_into(&count, items.data());
    if (result == VK_INCOMPLETE) continue;
    check(result, call);
    items.resize(count);
    return items;
  }
}

std::vector<VkExtensionProperties> instance_extensions(const char* layer) {
  return enumerate<VkExtensionProperties>("vkEnumerateInstanceExtensionProperties",
                                          [&](std::uint32_t* count, VkExtensionProperties* items) {
                                            return vkEnumerateInstanceExtensionProperties(layer, count, items);
                                          });
}

bool has_extension(const std::vector<VkExtensionProperties>& extensions, std::string_view name) {
  return std::any_of(extensions.begin(), extensions.end(),
                     [&](const VkExtensionProperties& e) { return name == e.extensionName; });
}

std::string_view type_name(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "CPU";
    default: return "other";
  }
}

bool is_gpu(VkPhysicalDeviceType type) {
  return type == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU || type == VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU ||
         type == VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU;
}

/// Auto's order: discrete, integrated, virtual GPU, then CPU, then anything else.
int auto_rank(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 3;
    default: return 4;
  }
}

std::string version_string(std::uint32_t version) {
  char text[32];
  std::snprintf(text, sizeof text, "%u.%u.%u", VK_API_VERSION_MAJOR(version), VK_API_VERSION_MINOR(version),
                VK_API_VERSION_PATCH(version));
  return text;
}

DevicePreference resolve_preference(DevicePreference requested) {
  if (requested != DevicePreference::Auto) return requested;
  const char* text = std::getenv("SOL_VK_DEVICE");
  if (text == nullptr || *text == '\0') return requested;
  const std::optional<DevicePreference> parsed = parse_device_preference(text);
  if (!parsed) {
    throw std::invalid_argument(std::string("SOL_VK_DEVICE must be gpu, cpu or auto, got '") + text + "'");
  }
  return *parsed;
}

VKAPI_ATTR VkBool32 VKAPI_CALL on_debug_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                VkDebugUtilsMessageTypeFlagsEXT types,
                                                const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  auto* device = static_cast<detail::Device*>(user);
  const std::string text = data != nullptr && data->pMessage != nullptr ? data->pMessage : "(no message)";
  const bool error = (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) != 0;
  // Only the validation layer's errors count; the loader's own complaints
  // (a broken driver manifest, say) are reported but are not our errors.
  if (error && (types & VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT) != 0) {
    const std::lock_guard lock(device->messages_mutex);
    device->validation_errors.push_back(text);
  }
  std::fprintf(stderr, "sol::vk: %s: %s\n", error ? "validation error" : "validation warning", text.c_str());
  return VK_FALSE;  // never abort the call
}

struct Candidate {
  VkPhysicalDevice handle = VK_NULL_HANDLE;
  VkPhysicalDeviceProperties properties{};
  std::uint32_t queue_family = 0;
  std::uint32_t timestamp_valid_bits = 0;
  std::string unusable;  // why it cannot be used; empty when it can
};

Candidate inspect(VkPhysicalDevice handle, const std::vector<std::string>& device_extensions) {
  Candidate c;
  c.handle = handle;
  vkGetPhysicalDeviceProperties(handle, &c.properties);
  if (c.properties.apiVersion < VK_API_VERSION_1_2) {
    c.unusable = "Vulkan " + version_string(c.properties.apiVersion) + " < 1.2";
    return c;
  }
  std::uint32_t family_count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(handle, &family_count, nullptr);
  std::vector<VkQueueFamilyProperties> families(family_count);
  vkGetPhysicalDeviceQueueFamilyProperties(handle, &family_count, families.data());
  // A queue with compute; one that also does graphics when there is one, so
  // that a presenter can use the same queue.
  int chosen = -1;
  for (std::uint32_t i = 0; i < family_count; ++i) {
    const VkQueueFlags flags = families[i].queueFlags;
    if ((flags & VK_QUEUE_COMPUTE_BIT) == 0 || families[i].queueCount == 0) continue;
    if (chosen < 0 || ((flags & VK_QUEUE_GRAPHICS_BIT) != 0 &&
                       (families[static_cast<std::uint32_t>(chosen)].queueFlags & VK_QUEUE_GRAPHICS_BIT) == 0)) {
      chosen = static_cast<int>(i);
    }
  }
  if (chosen < 0) {
    c.unusable = "no compute queue";
    return c;
  }
  c.queue_family = static_cast<std::uint32_t>(chosen);
  c.timestamp_valid_bits = families[c.queue_family].timestampValidBits;
  const auto extensions = enumerate<VkExtensionProperties>(
      "vkEnumerateDeviceExtensionProperties", [&](std::uint32_t* count, VkExtensionProperties* items) {
        return vkEnumerateDeviceExtensionProperties(handle, nullptr, count, items);
      });
  for (const std::string& name : device_extensions) {
    if (!has_extension(extensions, name)) {
      c.unusable = "no " + name;
      return c;
    }
  }
  return c;
}

std::string describe(const std::vector<Candidate>& candidates) {
  std::string text;
  for (const Candidate& c : candidates) {
    if (!text.empty()) text += ", ";
    text += "'" + std::string(c.properties.deviceName) + "' (" + std::string(type_name(c.properties.deviceType));
    if (!c.unusable.empty()) text += ", unusable: " + c.unusable;
    text += ")";
  }
  return text;
}

const Candidate& choose(const std::vector<Candidate>& candidates, DevicePreference preference) {
  const Candidate* best = nullptr;
  for (const Candidate& c : candidates) {
    if (!c.unusable.empty()) continue;
    const VkPhysicalDeviceType type = c.properties.deviceType;
    if (preference == DevicePreference::Gpu && !is_gpu(type)) continue;
    if (preference == DevicePreference::Cpu && type != VK_PHYSICAL_DEVICE_TYPE_CPU) continue;
    if (best == nullptr || auto_rank(type) < auto_rank(best->properties.deviceType)) best = &c;
  }
  if (best == nullptr) {
    const char* what = preference == DevicePreference::Gpu   ? "no usable Vulkan GPU"
                       : preference == DevicePreference::Cpu ? "no usable Vulkan CPU device"
                                                             : "no usable Vulkan device";
    throw VulkanError(VK_ERROR_INITIALIZATION_FAILED,
                      std::string(what) + " (devices found: " + describe(candidates) + ")");
  }
  return *best;
}

}  // namespace

std::optional<DevicePreference> parse_device_preference(std::string_view text) {
  std::string lower(text);
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  if (lower == "auto") return DevicePreference::Auto;
  if (lower == "gpu") return DevicePreference::Gpu;
  if (lower == "cpu") return DevicePreference::Cpu;
  return std::nullopt;
}

std::string_view to_string(DevicePreference preference) {
  switch (preference) {
    case DevicePreference::Gpu: return "gpu";
    case DevicePreference::Cpu: return "cpu";
    default: return "auto";
  }
}

namespace detail {

void Device::save_pipeline_cache() const {
  if (pipeline_cache == VK_NULL_HANDLE || pipeline_cache_path.empty()) return;
  std::size_t size = 0;
  if (vkGetPipelineCacheData(device, pipeline_cache, &size, nullptr) != VK_SUCCESS) return;
  std::vector<char> data(size);
  if (vkGetPipelineCacheData(device, pipeline_cache, &size, data.data()) != VK_SUCCESS) return;
  data.resize(size);
  namespace fs = std::filesystem;
  const fs::path path(pipeline_cache_path);
  std::error_code ec;
  if (path.has_parent_path()) fs::create_directories(path.parent_path(), ec);
  // Complete or absent: a temporary beside it (this process's), then renamed over it.
  const fs::path temporary = path.string() + ".tmp" + std::to_string(static_cast<long>(getpid()));
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out.write(data.data(), static_cast<std::streamsize>(data.size()));
    out.close();
    if (!out) {
      fs::remove(temporary, ec);
      std::fprintf(stderr, "sol::vk: warning: cannot write the pipeline cache %s (the next start compiles again)\n",
                   pipeline_cache_path.c_str());
      return;
    }
  }
  fs::rename(temporary, path, ec);
  if (ec) {
    fs::remove(temporary, ec);
    std::fprintf(stderr, "sol::vk: warning: cannot write the pipeline cache %s (the next start compiles again)\n",
                 pipeline_cache_path.c_str());
  }
}

Device::~Device() {
  if (device != VK_NULL_HANDLE) {
    vkDeviceWaitIdle(device);  // nothing may still run; the result does not matter here
    if (pipeline_cache != VK_NULL_HANDLE) {
      save_pipeline_cache();
      vkDestroyPipelineCache(device, pipeline_cache, nullptr);
    }
    if (timestamp_pool != VK_NULL_HANDLE) vkDestroyQueryPool(device, timestamp_pool, nullptr);
    if (command_pool != VK_NULL_HANDLE) vkDestroyCommandPool(device, command_pool, nullptr);
    if (owns_device) vkDestroyDevice(device, nullptr);
  }
  if (messenger != VK_NULL_HANDLE && destroy_messenger != nullptr) destroy_messenger(instance, messenger, nullptr);
  if (instance != VK_NULL_HANDLE && owns_device) vkDestroyInstance(instance, nullptr);
}

std::uint32_t Device::memory_type(std::uint32_t type_bits, VkMemoryPropertyFlags required,
                                  VkMemoryPropertyFlags preferred, const char* what) const {
  int fallback = -1;
  for (std::uint32_t i = 0; i < memory_properties.memoryTypeCount; ++i) {
    const VkMemoryPropertyFlags flags = memory_properties.memoryTypes[i].propertyFlags;
    if ((type_bits & (1u << i)) == 0 || (flags & required) != required) continue;
    if ((flags & preferred) == preferred) return i;
    if (fallback < 0) fallback = static_cast<int>(i);
  }
  if (fallback < 0) {
    throw VulkanError(VK_ERROR_OUT_OF_DEVICE_MEMORY, std::string(what) + ": no suitable memory type on this device");
  }
  return static_cast<std::uint32_t>(fallback);
}

double Device::submit_and_wait(const std::function<void(VkCommandBuffer)>& record) {
  // A fresh command buffer and fence per submission: nothing to reset, and a
  // failure half-way leaves nothing behind (the guard frees both).
  struct Submission {
    VkDevice device;
    VkCommandPool pool;
    VkCommandBuffer commands = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
    ~Submission() {
      if (fence != VK_NULL_HANDLE) vkDestroyFence(device, fence, nullptr);
      if (commands != VK_NULL_HANDLE) vkFreeCommandBuffers(device, pool, 1, &commands);
    }
  } submission{device, command_pool};

  VkCommandBufferAllocateInfo allocate{};

  allocate.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
  allocate.commandPool = command_pool;
  allocate.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  allocate.commandBufferCount = 1;
  check(vkAllocateCommandBuffers(device, &allocate, &submission.commands), "vkAllocateCommandBuffers");
  VkFenceCreateInfo fence_info{};
  fence_info.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
  check(vkCreateFence(device, &fence_info, nullptr, &submission.fence), "vkCreateFence");

  VkCommandBuffer commands = submission.commands;
  VkCommandBufferBeginInfo begin{};
  begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(vkBeginCommandBuffer(commands, &begin), "vkBeginCommandBuffer");
  if (timestamp_pool != VK_NULL_HANDLE) {
    vkCmdResetQueryPool(commands, timestamp_pool, 0, 2);
    vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, timestamp_pool, 0);
  }
  record(commands);
  if (timestamp_pool != VK_NULL_HANDLE) {
    vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, timestamp_pool, 1);
  }
  check(vkEndCommandBuffer(commands), "vkEndCommandBuffer");

  VkSubmitInfo submit{};

  submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &commands;
  const auto start = std::chrono::steady_clock::now();
  check(vkQueueSubmit(queue, 1, &submit, submission.fence), "vkQueueSubmit");
  check(vkWaitForFences(device, 1, &submission.fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  const double host_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  if (timestamp_pool == VK_NULL_HANDLE) return host_ms;

  std::uint64_t ticks[2] = {0, 0};
  check(vkGetQueryPoolResults(device, timestamp_pool, 0, 2, sizeof(ticks), ticks, sizeof(std::uint64_t),
                              VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
        "vkGetQueryPoolResults");
  return elapsed_ms(ticks[0], ticks[1]);
}

double Device::elapsed_ms(std::uint64_t from, std::uint64_t to) const {
  // Only the low timestampValidBits bits count; unsigned subtraction under the
  // mask also survives a wrap-around.
  const std::uint64_t mask = timestamp_valid_bits >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << timestamp_valid_bits) - 1;
  const std::uint64_t elapsed = (to - from) & mask;
  return static_cast<double>(elapsed) * static_cast<double>(properties.limits.timestampPeriod) * 1e-6;
}

}  // namespace detail

namespace {

// The device's pipeline cache: the file's contents in `dir` when this device
// and driver wrote it, else empty (a foreign or broken file is warned about
// and rewritten later).
void create_pipeline_cache(detail::Device& d, const std::string& dir) {
  std::vector<char> initial;
  if (!dir.empty()) {
    char name[96];
    std::snprintf(name, sizeof name, "pipelines-%04x-%04x-%08x.bin", d.properties.vendorID, d.properties.deviceID,
                  d.properties.driverVersion);
    d.pipeline_cache_path = (std::filesystem::path(dir) / name).string();
    initial = read_pipeline_cache(d.pipeline_cache_path);
    if (!initial.empty()) {
      // VkPipelineCacheHeaderVersionOne: header size, version, vendor, device, cache UUID (32 bytes).
      std::uint32_t header[4] = {};
      const bool sized = initial.size() >= 16 + VK_UUID_SIZE;
      if (sized) std::memcpy(header, initial.data(), sizeof header);
      const bool ours = sized && header[0] >= 16 + VK_UUID_SIZE && header[0] <= initial.size() &&
                        header[1] == VK_PIPELINE_CACHE_HEADER_VERSION_ONE && header[2] == d.properties.vendorID &&
                        header[3] == d.properties.deviceID &&
                        std::memcmp(initial.data() + 16, d.properties.pipelineCacheUUID, VK_UUID_SIZE) == 0;
      if (!ours) {
        std::fprintf(stderr,
                     "sol::vk: warning: ignoring the pipeline cache %s: %s (it is rewritten for this device)\n",
                     d.pipeline_cache_path.c_str(),
                     sized && header[1] == VK_PIPELINE_CACHE_HEADER_VERSION_ONE && header[0] >= 16 + VK_UUID_SIZE &&
                             header[0] <= initial.size()
                         ? "written by another device or driver"
                         : "truncated or not a pipeline cache");
        initial.clear();
      }
    }
  }
  VkPipelineCacheCreateInfo cache_info{};
  cache_info.sType = VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO;
  cache_info.initialDataSize = initial.size();
  cache_info.pInitialData = initial.empty() ? nullptr : initial.data();
  if (vkCreatePipelineCache(d.device, &cache_info, nullptr, &d.pipeline_cache) != VK_SUCCESS) {
    // A cache the driver refuses: start empty rather than fail.
    cache_info.initialDataSize = 0;
    cache_info.pInitialData = nullptr;
    initial.clear();
    check(vkCreatePipelineCache(d.device, &cache_info, nullptr, &d.pipeline_cache), "vkCreatePipelineCache");
  }
  d.pipeline_cache_loaded = initial.size();
}

}  // namespace

namespace {

// What a Context makes on its device, its own or an application's: the
// command pool, the pipeline cache and the timestamp queries.
void create_device_objects(detail::Device& d, const std::string& pipeline_cache_dir, std::uint32_t timestamp_valid_bits) {
  VkCommandPoolCreateInfo pool_info{};
  pool_info.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
  pool_info.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
  pool_info.queueFamilyIndex = d.queue_family;
  check(vkCreateCommandPool(d.device, &pool_info, nullptr, &d.command_pool), "vkCreateCommandPool");

  create_pipeline_cache(d, pipeline_cache_dir);

  if (timestamp_valid_bits > 0 && d.properties.limits.timestampPeriod > 0.0f) {
    VkQueryPoolCreateInfo query_info{};
    query_info.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO;
    query_info.queryType = VK_QUERY_TYPE_TIMESTAMP;
    query_info.queryCount = 2;
    check(vkCreateQueryPool(d.device, &query_info, nullptr, &d.timestamp_pool), "vkCreateQueryPool");
    d.timestamp_valid_bits = timestamp_valid_bits;
  }
}

}  // namespace

Context::Context(const ContextOptions& options) : m_device(std::make_shared<detail::Device>()) {
  detail::Device& d = *m_device;
  const DevicePreference preference = resolve_preference(options.preference);

  // --- instance: API 1.2, validation when asked for and installed ---
  std::vector<const char*> layers;
  std::vector<const char*> extensions;
  for (const std::string& name : options.instance_extensions) extensions.push_back(name.c_str());
  bool validation_features = false;
  if (options.validation) {
    const auto available = enumerate<VkLayerProperties>(
        "vkEnumerateInstanceLayerProperties",
        [](std::uint32_t* count, VkLayerProperties* items) { return vkEnumerateInstanceLayerProperties(count, items); });
    const bool present = std::any_of(available.begin(), available.end(),
                                     [](const VkLayerProperties& l) { return std::string_view(l.layerName) == kValidationLayer; });
    if (present) {
      const auto layer_extensions = instance_extensions(kValidationLayer);
      const auto global_extensions = instance_extensions(nullptr);
      if (has_extension(layer_extensions, VK_EXT_DEBUG_UTILS_EXTENSION_NAME) ||
          has_extension(global_extensions, VK_EXT_DEBUG_UTILS_EXTENSION_NAME)) {
        layers.push_back(kValidationLayer);
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
        validation_features = has_extension(layer_extensions, VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
        if (validation_features) extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
        d.validation = true;
      } else {
        std::fprintf(stderr, "sol::vk: warning: validation requested but %s is missing; running without validation\n",
                     VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
      }
    } else {
      std::fprintf(stderr,
                   "sol::vk: warning: validation requested but %s is not installed (Debian: vulkan-validationlayers); "
                   "running without validation\n",
                   kValidationLayer);
    }
  }

  VkApplicationInfo app{};

  app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
  app.pApplicationName = "Sol";
  app.pEngineName = "Sol::vk";
  app.apiVersion = VK_API_VERSION_1_2;

  VkDebugUtilsMessengerCreateInfoEXT messenger_info{};

  messenger_info.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT;
  messenger_info.messageSeverity =
      VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  messenger_info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                               VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                               VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  messenger_info.pfnUserCallback = on_debug_message;
  messenger_info.pUserData = &d;
  // Synchronisation validation: catches missing or wrong barriers.
  const VkValidationFeatureEnableEXT enabled_features[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
  VkValidationFeaturesEXT features{};
  features.sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT;
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = enabled_features;
  if (validation_features) messenger_info.pNext = &features;

  VkInstanceCreateInfo instance_info{};

  instance_info.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
  instance_info.pApplicationInfo = &app;
  instance_info.enabledLayerCount = static_cast<std::uint32_t>(layers.size());
  instance_info.ppEnabledLayerNames = layers.data();
  instance_info.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
  instance_info.ppEnabledExtensionNames = extensions.data();
  // Chained here too so that instance creation and destruction are validated.
  if (d.validation) instance_info.pNext = &messenger_info;
  guard_driver_shader_cache();
  const VkResult created = options.create_instance ? options.create_instance(instance_info, &d.instance)
                                                   : vkCreateInstance(&instance_info, nullptr, &d.instance);
  if (created == VK_ERROR_INCOMPATIBLE_DRIVER) {
    throw VulkanError(created,
                      "no Vulkan 1.2 driver found (vkCreateInstance failed: VK_ERROR_INCOMPATIBLE_DRIVER); install "
                      "one, for example Mesa's lavapipe (Debian: mesa-vulkan-drivers)");
  }
  check(created, "vkCreateInstance");

  if (d.validation) {
    auto create_messenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(d.instance, "vkCreateDebugUtilsMessengerEXT"));
    d.destroy_messenger = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(d.instance, "vkDestroyDebugUtilsMessengerEXT"));
    if (create_messenger == nullptr || d.destroy_messenger == nullptr) {
      throw VulkanError("vkGetInstanceProcAddr(vkCreateDebugUtilsMessengerEXT)", VK_ERROR_EXTENSION_NOT_PRESENT);
    }
    messenger_info.pNext = nullptr;
    check(create_messenger(d.instance, &messenger_info, nullptr, &d.messenger), "vkCreateDebugUtilsMessengerEXT");
  }

  // --- physical device ---
  const auto handles = enumerate<VkPhysicalDevice>("vkEnumeratePhysicalDevices",
                                                   [&](std::uint32_t* count, VkPhysicalDevice* items) {
                                                     return vkEnumeratePhysicalDevices(d.instance, count, items);
                                                   });
  if (handles.empty()) {
    throw VulkanError(VK_ERROR_INITIALIZATION_FAILED,
                      "no Vulkan device found; install a driver, for example Mesa's lavapipe (Debian: "
                      "mesa-vulkan-drivers)");
  }
  std::vector<Candidate> candidates;
  for (VkPhysicalDevice handle : handles) candidates.push_back(inspect(handle, options.device_extensions));
  Candidate given;  // the hook's choice
  if (options.choose_physical_device) {
    const VkPhysicalDevice handle = options.choose_physical_device(d.instance);
    if (handle == VK_NULL_HANDLE) {
      throw VulkanError(VK_ERROR_INITIALIZATION_FAILED, "no Vulkan device was given (devices found: " +
                                                            describe(candidates) + ")");
    }
    given = inspect(handle, options.device_extensions);
    if (!given.unusable.empty()) {
      throw VulkanError(VK_ERROR_INITIALIZATION_FAILED, "the Vulkan device given, '" +
                                                            std::string(given.properties.deviceName) +
                                                            "', is unusable: " + given.unusable);
    }
  }
  const Candidate& chosen = options.choose_physical_device ? given : choose(candidates, preference);
  d.physical_device = chosen.handle;
  d.properties = chosen.properties;
  d.name = chosen.properties.deviceName;
  d.queue_family = chosen.queue_family;
  vkGetPhysicalDeviceMemoryProperties(d.physical_device, &d.memory_properties);

  // --- logical device, queue, command pool, timestamp queries ---
  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queue_info{};
  queue_info.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
  queue_info.queueFamilyIndex = d.queue_family;
  queue_info.queueCount = 1;
  queue_info.pQueuePriorities = &priority;
  std::vector<const char*> device_extensions;
  for (const std::string& name : options.device_extensions) device_extensions.push_back(name.c_str());
  // Optional features, enabled when the device has them: writes to storage
  // images declared without a format qualifier (march.comp's 8-bit sRGB
  // output for presenters, whose swapchain formats GLSL cannot name).
  VkPhysicalDeviceFeatures supported{};
  vkGetPhysicalDeviceFeatures(d.physical_device, &supported);
  VkPhysicalDeviceFeatures enabled{};
  enabled.shaderStorageImageWriteWithoutFormat = supported.shaderStorageImageWriteWithoutFormat;
  d.storage_write_without_format = supported.shaderStorageImageWriteWithoutFormat == VK_TRUE;
  VkDeviceCreateInfo device_info{};
  device_info.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
  device_info.pEnabledFeatures = &enabled;
  device_info.queueCreateInfoCount = 1;
  device_info.pQueueCreateInfos = &queue_info;
  device_info.enabledExtensionCount = static_cast<std::uint32_t>(device_extensions.size());
  device_info.ppEnabledExtensionNames = device_extensions.data();
  check(options.create_device ? options.create_device(d.physical_device, device_info, &d.device)
                              : vkCreateDevice(d.physical_device, &device_info, nullptr, &d.device),
        "vkCreateDevice");
  vkGetDeviceQueue(d.device, d.queue_family, 0, &d.queue);

  create_device_objects(d, options.pipeline_cache_dir, chosen.timestamp_valid_bits);
}

Context::Context(const ExternalDevice& external) : m_device(std::make_shared<detail::Device>()) {
  if (external.instance == VK_NULL_HANDLE || external.physical_device == VK_NULL_HANDLE ||
      external.device == VK_NULL_HANDLE) {
    throw std::invalid_argument("sol::vk::Context: ExternalDevice needs the instance, physical_device and device");
  }
  detail::Device& d = *m_device;
  d.owns_device = false;
  d.instance = external.instance;
  d.physical_device = external.physical_device;
  vkGetPhysicalDeviceProperties(d.physical_device, &d.properties);
  d.name = d.properties.deviceName;
  if (d.properties.apiVersion < VK_API_VERSION_1_2) {
    throw VulkanError(VK_ERROR_INITIALIZATION_FAILED, "sol::vk::Context: the application's device '" + d.name +
                                                          "' has Vulkan " + version_string(d.properties.apiVersion) +
                                                          "; Sol needs 1.2");
  }
  std::uint32_t family_count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(d.physical_device, &family_count, nullptr);
  std::vector<VkQueueFamilyProperties> families(family_count);
  vkGetPhysicalDeviceQueueFamilyProperties(d.physical_device, &family_count, families.data());
  if (external.queue_family >= family_count || (families[external.queue_family].queueFlags & VK_QUEUE_COMPUTE_BIT) == 0 ||
      external.queue_index >= families[external.queue_family].queueCount) {
    throw VulkanError(VK_ERROR_INITIALIZATION_FAILED,
                      "sol::vk::Context: the application's queue (family " + std::to_string(external.queue_family) +
                          ", index " + std::to_string(external.queue_index) + ") is not a compute queue of '" + d.name + "'");
  }
  d.device = external.device;
  d.queue_family = external.queue_family;
  vkGetDeviceQueue(d.device, d.queue_family, external.queue_index, &d.queue);
  vkGetPhysicalDeviceMemoryProperties(d.physical_device, &d.memory_properties);
  d.storage_write_without_format = external.storage_write_without_format;
  create_device_objects(d, external.pipeline_cache_dir, families[d.queue_family].timestampValidBits);
}

Context::~Context() = default;

VkPipelineCache Context::pipeline_cache() const { return m_device->pipeline_cache; }
const VkPhysicalDeviceProperties& Context::properties() const { return m_device->properties; }
const std::string& Context::pipeline_cache_path() const { return m_device->pipeline_cache_path; }
std::size_t Context::pipeline_cache_loaded_bytes() const { return m_device->pipeline_cache_loaded; }

std::string default_pipeline_cache_dir() {
  const char* off = std::getenv("SOL_PIPELINE_CACHE");
  if (off && std::string(off) == "off") return {};
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return (std::filesystem::path(xdg) / "sol").string();
  if (const char* home = std::getenv("HOME"); home && *home) {
    return (std::filesystem::path(home) / ".cache" / "sol").string();
  }
  return {};
}
Context::Context(Context&&) noexcept = default;
Context& Context::operator=(Context&&) noexcept = default;

const std::string& Context::device_name() const { return m_device->name; }
VkPhysicalDeviceType Context::device_type() const { return m_device->properties.deviceType; }
bool Context::is_cpu() const { return m_device->properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU; }
std::uint32_t Context::api_version() const { return m_device->properties.apiVersion; }
bool Context::timestamps_supported() const { return m_device->timestamp_pool != VK_NULL_HANDLE; }
float Context::timestamp_period() const { return m_device->properties.limits.timestampPeriod; }
const VkPhysicalDeviceLimits& Context::limits() const { return m_device->properties.limits; }
bool Context::validation_enabled() const { return m_device->validation; }
bool Context::storage_write_without_format() const { return m_device->storage_write_without_format; }

std::vector<std::string> Context::validation_errors() const {
  const std::lock_guard lock(m_device->messages_mutex);
  return m_device->validation_errors;
}

double Context::submit_and_wait(const std::function<void(VkCommandBuffer)>& record) {
  return m_device->submit_and_wait(record);
}
void Context::wait_idle() { check(vkDeviceWaitIdle(m_device->device), "vkDeviceWaitIdle"); }

VkInstance Context::instance() const { return m_device->instance; }
VkPhysicalDevice Context::physical_device() const { return m_device->physical_device; }
VkDevice Context::device() const { return m_device->device; }
VkQueue Context::queue() const { return m_device->queue; }
std::uint32_t Context::queue_family_index() const { return m_device->queue_family; }

}  // namespace sol::vk
