// A 2D storage image for compute shaders to write, with download to the host.
//
// The image lives in device memory with usage STORAGE | TRANSFER_SRC. It is
// in VK_IMAGE_LAYOUT_GENERAL (the layout storage images need) from creation
// on, between any two commands of Sol::vk: code that records its own commands
// finds it in GENERAL and must leave it there.
#pragma once

#include <cstdint>
#include <cstddef>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include <vulkan/vulkan_core.h>

namespace sol::vk {

class Context;
namespace detail {
struct Device;
}

class StorageImage {
 public:
  /// Throws std::invalid_argument for a zero or too large extent, VulkanError
  /// when the device cannot use `format` as a storage image.
  StorageImage(Context& context, std::uint32_t width, std::uint32_t height,
               VkFormat format = VK_FORMAT_R32G32B32A32_SFLOAT);
  ~StorageImage();
  StorageImage(StorageImage&& other) noexcept;
  StorageImage& operator=(StorageImage&& other) noexcept;
  StorageImage(const StorageImage&) = delete;
  StorageImage& operator=(const StorageImage&) = delete;

  std::uint32_t width() const { return m_width; }
  std::uint32_t height() const { return m_height; }
  VkFormat format() const { return m_format; }
  VkImage handle() const { return m_image; }
  VkImageView view() const { return m_view; }
  /// This image's identity: unique among the process's buffers and images,
  /// never reused; 0 after a move from it (Buffer::id).
  std::uint64_t id() const { return m_id; }
  /// VK_IMAGE_LAYOUT_GENERAL, the layout between commands.
  VkImageLayout layout() const { return VK_IMAGE_LAYOUT_GENERAL; }

  /// The float channels per pixel of a 32-bit float format (R32, R32G32,
  /// R32G32B32A32 SFLOAT); 0 for any other format.
  std::uint32_t float_channels() const;

  /// Copies the image to the host after all work submitted before: pixels
  /// row by row from the top (y = 0), channels interleaved,
  /// width·height·float_channels() values. Throws std::logic_error for a
  /// format that is not 32-bit float.
  std::vector<float> download() const;
  /// The same band by band, without holding the whole image: each band of
  /// rows (at most 16 MiB, a row at least) of rows [first, first + count)
  /// (count 0: to the last row) is copied to the host and handed to `band`
  /// as (first row, rows, their values), from the top; the next band is
  /// copied once it returns. Same errors as download(), and
  /// std::out_of_range for rows outside the image.
  void download_rows(const std::function<void(std::uint32_t first_row, std::uint32_t rows, std::span<const float> values)>& band,
                     std::uint32_t first = 0, std::uint32_t count = 0) const;
  /// The same for an 8-bit R8G8B8A8_UNORM or B8G8R8A8_UNORM image: 4 bytes
  /// per pixel in the format's channel order. Throws std::logic_error for
  /// other formats.
  std::vector<std::uint8_t> download_bytes() const;

 private:
  void release() noexcept;
  void copy_to_host(std::span<std::byte> out) const;
  // Copies rows [first, first + count) band by band through one staging
  // buffer, handing each band's bytes to `band`.
  void copy_bands(std::size_t texel_bytes, std::uint32_t first, std::uint32_t count,
                  const std::function<void(std::uint32_t, std::uint32_t, std::span<const std::byte>)>& band) const;

  std::shared_ptr<detail::Device> m_owner;
  VkImage m_image = VK_NULL_HANDLE;
  VkDeviceMemory m_memory = VK_NULL_HANDLE;
  VkImageView m_view = VK_NULL_HANDLE;
  std::uint32_t m_width = 0;
  std::uint32_t m_height = 0;
  VkFormat m_format = VK_FORMAT_UNDEFINED;
  std::uint64_t m_id = 0;
};

/// Records one image memory barrier (colour aspect, mip 0, layer 0, no queue
/// family transfer): the presenters' and StorageImage's layout changes and
/// hand-overs between stages, each written as (stage, access) before and after.
void image_barrier(VkCommandBuffer commands, VkImage image, VkPipelineStageFlags src_stage, VkAccessFlags src_access,
                   VkPipelineStageFlags dst_stage, VkAccessFlags dst_access, VkImageLayout from, VkImageLayout to);

}  // namespace sol::vk
