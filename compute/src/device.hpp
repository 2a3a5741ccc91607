// The state behind a sol::vk::Context (not installed). Buffers, images and
// pipelines share its ownership, so the device outlives them all and the
// Context object itself may be moved or destroyed first.
#pragma once

#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include <vulkan/vulkan_core.h>

namespace sol::vk::detail {

/// A new identity for a buffer or image: never 0, never given twice in the
/// process (Buffer::id, StorageImage::id).
std::uint64_t next_resource_id();

struct Device {
  Device() = default;
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;
  /// Destroys whatever was created, in reverse order (also after a failed
  /// construction).
  ~Device();

  /// A memory type index allowed by `type_bits` with all `required` flags,
  /// one that also has `preferred` when there is one. Throws VulkanError.
  std::uint32_t memory_type(std::uint32_t type_bits, VkMemoryPropertyFlags required,
                            VkMemoryPropertyFlags preferred, const char* what) const;

  /// See Context::submit_and_wait.
  double submit_and_wait(const std::function<void(VkCommandBuffer)>& record);
  /// Milliseconds between two timestamps of the queue: only the low
  /// timestamp_valid_bits bits count, and the unsigned difference under
  /// that mask also survives a wrap-around (FrameTimer::elapsed_ms).
  double elapsed_ms(std::uint64_t from, std::uint64_t to) const;

  VkInstance instance = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  PFN_vkDestroyDebugUtilsMessengerEXT destroy_messenger = nullptr;
  VkPhysicalDevice physical_device = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  std::uint32_t queue_family = 0;
  VkCommandPool command_pool = VK_NULL_HANDLE;
  VkQueryPool timestamp_pool = VK_NULL_HANDLE;  // two queries: before, after; null when unsupported
  std::uint32_t timestamp_valid_bits = 0;
  VkPhysicalDeviceProperties properties{};
  std::string name;  // properties.deviceName
  VkPhysicalDeviceMemoryProperties memory_properties{};
  bool validation = false;
  bool owns_device = true;  // false: an application's device and instance (ExternalDevice), not destroyed here
  bool storage_write_without_format = false;  // shaderStorageImageWriteWithoutFormat, enabled

  VkPipelineCache pipeline_cache = VK_NULL_HANDLE;
  std::string pipeline_cache_path;  // where the cache is written back (empty: not kept)
  std::size_t pipeline_cache_loaded = 0;
  /// Writes the cache to pipeline_cache_path (a temporary, then renamed);
  /// a failure is a warning on stderr.
  void save_pipeline_cache() const;

  mutable std::mutex messages_mutex;  // the debug messenger may call from any thread
  std::vector<std::string> validation_errors;
};

}  // namespace sol::vk::detail
