// The Vulkan instance, the chosen physical device and its logical device.
//
// A Context is the first object of Sol::vk: it creates a Vulkan 1.2 instance,
// picks one physical device, creates a logical device with one queue that
// supports compute, and submits work to it. Buffers, images and pipelines are
// created from a Context and share ownership of its device: whatever order
// they are destroyed in, the device goes last. A Context and the objects made
// from it are for one thread at a time. An application with a Vulkan device
// of its own hands it over instead (ExternalDevice) and keeps it.
//
// Device choice: ContextOptions::preference, where Auto (the default) takes a
// GPU (discrete before integrated before virtual) when there is one and else
// the CPU device (Mesa's lavapipe); the environment variable
// SOL_VK_DEVICE=gpu|cpu|auto overrides Auto (and only Auto). Only devices
// with Vulkan 1.2, a compute queue and the requested device extensions count.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <vulkan/vulkan_core.h>

namespace sol::vk {

namespace detail {
struct Device;
}

enum class DevicePreference { Auto, Gpu, Cpu };

/// "auto", "gpu" or "cpu" (any case); std::nullopt for anything else.
std::optional<DevicePreference> parse_device_preference(std::string_view text);
std::string_view to_string(DevicePreference preference);

class Context;
/// Where the programs keep their pipeline caches: $XDG_CACHE_HOME/sol, else
/// ~/.cache/sol; empty when neither variable is set, or when
/// SOL_PIPELINE_CACHE=off.
std::string default_pipeline_cache_dir();

struct ContextOptions {
  DevicePreference preference = DevicePreference::Auto;
  /// Enables VK_LAYER_KHRONOS_validation (with synchronisation validation)
  /// and collects its error messages, see Context::validation_errors(). When
  /// the layer is not installed this prints a warning on stderr and goes on
  /// without it.
  bool validation = false;
  /// Extra extensions to enable, for example a presenter's surface and
  /// swapchain extensions. Devices lacking a device extension are not chosen.
  std::vector<std::string> instance_extensions{};
  std::vector<std::string> device_extensions{};
  /// A directory for the pipeline cache kept between runs (empty: none,
  /// the default; default_pipeline_cache_dir() is the programs'). The file
  /// in it, pipelines-VENDOR-DEVICE-DRIVER.bin, is one per device and driver
  /// version (the driver keys each pipeline inside by the kernel's SPIR-V and
  /// specialisation). It is read at construction when this device and driver
  /// wrote it (VkPipelineCacheHeaderVersionOne: vendor, device, cache UUID);
  /// a truncated, garbage or foreign file is ignored with a warning on
  /// stderr. Every pipeline is created through the cache, and the cache is
  /// written back (a temporary, then renamed) when the Context ends; a
  /// directory that cannot be written gives a warning, never an error.
  std::string pipeline_cache_dir;

  /// Hooks for a caller that must put the Context on objects someone else
  /// creates, such as an OpenXR runtime (XR_KHR_vulkan_enable2:
  /// xrCreateVulkanInstanceKHR, xrGetVulkanGraphicsDevice2KHR,
  /// xrCreateVulkanDeviceKHR). Each is given the create info the Context
  /// built (layers, extensions, API version 1.2) and must create the object
  /// from it, extending it as it needs to; the Context owns and destroys
  /// what they return. Unset hooks take the default path (vkCreateInstance,
  /// the device choice above, vkCreateDevice). A chosen physical device that
  /// is unusable (no Vulkan 1.2, no compute queue, a missing extension) makes
  /// the constructor throw VulkanError naming why.
  std::function<VkResult(const VkInstanceCreateInfo& info, VkInstance* instance)> create_instance{};
  std::function<VkPhysicalDevice(VkInstance instance)> choose_physical_device{};
  std::function<VkResult(VkPhysicalDevice physical_device, const VkDeviceCreateInfo& info, VkDevice* device)>
      create_device{};
};

/// An application's own Vulkan objects, which a Context adopts instead of
/// creating its own (Context(const ExternalDevice&)): Sol's pipelines,
/// buffers and images are then made on the application's device and its
/// commands recorded into the application's command buffers
/// (MarchRenderer::record) or submitted to the given queue. The application
/// keeps ownership: it destroys the device (and instance) after every Sol
/// object made from them. The device must be Vulkan 1.2 or newer; the queue
/// family must support compute.
struct ExternalDevice {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physical_device = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  std::uint32_t queue_family = 0;
  std::uint32_t queue_index = 0;
  /// Whether the application enabled shaderStorageImageWriteWithoutFormat
  /// (MarchRenderer's 8-bit sRGB output into UnormTarget images needs it).
  bool storage_write_without_format = false;
  /// As ContextOptions::pipeline_cache_dir.
  std::string pipeline_cache_dir{};
};

class Context {
 public:
  /// Throws VulkanError when there is no Vulkan driver or device, or no
  /// device meets the preference (the message lists the devices found), and
  /// std::invalid_argument when SOL_VK_DEVICE has a value other than
  /// gpu, cpu or auto.
  explicit Context(const ContextOptions& options = {});
  /// A Context on an application's device (see ExternalDevice), which it
  /// does not destroy; its own command pool, timestamp queries and pipeline
  /// cache are made on that device and destroyed with it. Throws
  /// std::invalid_argument for a null handle and VulkanError for a device
  /// below Vulkan 1.2 or a queue family without compute.
  explicit Context(const ExternalDevice& external);
  ~Context();
  Context(Context&&) noexcept;
  Context& operator=(Context&&) noexcept;
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  const std::string& device_name() const;
  VkPhysicalDeviceType device_type() const;
  /// True for a CPU implementation such as lavapipe.
  bool is_cpu() const;
  /// The device's Vulkan version (VK_API_VERSION_MAJOR/MINOR/PATCH decode it).
  std::uint32_t api_version() const;
  /// Whether the queue writes timestamps; when it does not, timings are host times.
  bool timestamps_supported() const;
  /// Nanoseconds per timestamp tick (VkPhysicalDeviceLimits::timestampPeriod).
  float timestamp_period() const;
  const VkPhysicalDeviceLimits& limits() const;
  /// The device's properties (vendor, device and driver ids, pipeline cache UUID, ...).
  const VkPhysicalDeviceProperties& properties() const;

  /// Whether the validation layer is active (requested and installed).
  bool validation_enabled() const;
  /// Whether shaders may write storage images declared without a format
  /// qualifier (the shaderStorageImageWriteWithoutFormat feature, enabled
  /// whenever the device has it).
  bool storage_write_without_format() const;
  /// Error messages the validation layer reported so far, oldest first.
  std::vector<std::string> validation_errors() const;

  /// Records commands with `record` into a fresh primary command buffer,
  /// submits it, waits for it to finish and returns its duration in
  /// milliseconds: from timestamps written before and after the recorded
  /// commands when supported, else the host time from submit to completion.
  double submit_and_wait(const std::function<void(VkCommandBuffer)>& record);
  /// Waits until the device is idle.
  void wait_idle();

  /// Raw handles, for code that records its own commands (a presenter).
  VkInstance instance() const;
  VkPhysicalDevice physical_device() const;
  VkDevice device() const;
  VkQueue queue() const;
  std::uint32_t queue_family_index() const;
  /// The pipeline cache every pipeline is created through (VK_NULL_HANDLE: none).
  VkPipelineCache pipeline_cache() const;
  /// The cache's file (empty: none kept) and the bytes read from it at
  /// construction (0: none, or ignored).
  const std::string& pipeline_cache_path() const;
  std::size_t pipeline_cache_loaded_bytes() const;

  /// Library internals; not part of the API.
  const std::shared_ptr<detail::Device>& internals() const { return m_device; }

 private:
  std::shared_ptr<detail::Device> m_device;
};

}  // namespace sol::vk
