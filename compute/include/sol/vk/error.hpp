// Errors thrown by Sol::vk.
//
// Every VkResult the library receives is checked: a failure throws
// sol::vk::VulkanError whose message names the call and the result, e.g.
// "vkCreateDevice failed: VK_ERROR_INITIALIZATION_FAILED". Misuse of the API
// (a binding of the wrong type, a push-constant block of the wrong size, a
// buffer access out of range) throws the standard exception that says so
// (std::invalid_argument, std::out_of_range, std::logic_error).
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

#include <vulkan/vulkan_core.h>

namespace sol::vk {

class VulkanError : public std::runtime_error {
 public:
  /// "<call> failed: <result name>".
  VulkanError(std::string_view call, VkResult result);
  /// A failure with its own message (no device found, SPIR-V rejected before
  /// it reached the driver, ...); `result` says what Vulkan would call it.
  VulkanError(VkResult result, const std::string& message);

  VkResult result() const { return m_result; }

 private:
  VkResult m_result;
};

/// The enumerant's name, e.g. "VK_ERROR_DEVICE_LOST"; "VkResult(<n>)" for
/// values this build does not know.
std::string result_name(VkResult result);

/// Throws VulkanError(call, result) unless `result` is VK_SUCCESS.
inline void check(VkResult result, std::string_view call) {
  if (result != VK_SUCCESS) throw VulkanError(call, result);
}

}  // namespace sol::vk
