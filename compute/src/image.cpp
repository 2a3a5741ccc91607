#include "sol/vk/image.hpp"

#include <algorithm>

#include <cstring>
#include <stdexcept>
#include <span>
#include <string>
#include <utility>

#include "device.hpp"
#include "sol/vk/buffer.hpp"
#include "sol/vk/context.hpp"
#include "sol/vk/error.hpp"

namespace sol::vk {
namespace {

std::string format_name(VkFormat format) {
  switch (format) {
    case VK_FORMAT_R32_SFLOAT: return "VK_FORMAT_R32_SFLOAT";
    case VK_FORMAT_R32G32_SFLOAT: return "VK_FORMAT_R32G32_SFLOAT";
    case VK_FORMAT_R32G32B32A32_SFLOAT: return "VK_FORMAT_R32G32B32A32_SFLOAT";
    case VK_FORMAT_R16G16B16A16_SFLOAT: return "VK_FORMAT_R16G16B16A16_SFLOAT";
    case VK_FORMAT_R8G8B8A8_UNORM: return "VK_FORMAT_R8G8B8A8_UNORM";
    case VK_FORMAT_B8G8R8A8_UNORM: return "VK_FORMAT_B8G8R8A8_UNORM";
    case VK_FORMAT_R8G8B8A8_SRGB: return "VK_FORMAT_R8G8B8A8_SRGB";
    default: return "VkFormat(" + std::to_string(static_cast<int>(format)) + ")";
  }
}

std::uint32_t float_channels_of(VkFormat format) {
  switch (format) {
    case VK_FORMAT_R32_SFLOAT: return 1;
    case VK_FORMAT_R32G32_SFLOAT: return 2;
    case VK_FORMAT_R32G32B32A32_SFLOAT: return 4;
    default: return 0;
  }
}

constexpr VkImageSubresourceRange kColor{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};

}  // namespace

StorageImage::StorageImage(Context& context, std::uint32_t width, std::uint32_t height, VkFormat format)
    : m_owner(context.internals()), m_width(width), m_height(height), m_format(format), m_id(detail::next_resource_id()) {
  detail::Device& d = *m_owner;
  const std::uint32_t max_extent = d.properties.limits.maxImageDimension2D;
  if (width == 0 || height == 0 || width > max_extent || height > max_extent) {
    throw std::invalid_argument("StorageImage: extent " + std::to_string(width) + "x" + std::to_string(height) +
                                " outside [1, " + std::to_string(max_extent) + "]");
  }
  VkFormatProperties support{};
  vkGetPhysicalDeviceFormatProperties(d.physical_device, format, &support);
  const VkFormatFeatureFlags needed = VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT | VK_FORMAT_FEATURE_TRANSFER_SRC_BIT;
  if ((support.optimalTilingFeatures & needed) != needed) {
    throw VulkanError(VK_ERROR_FORMAT_NOT_SUPPORTED,
                      "StorageImage: " + d.name + " cannot use " + format_name(format) + " as a storage image");
  }
  try {
    VkImageCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = format;
    info.extent = {width, height, 1};
    info.mipLevels = 1;
    info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    check(vkCreateImage(d.device, &info, nullptr, &m_image), "vkCreateImage");

    VkMemoryRequirements requirements{};
    vkGetImageMemoryRequirements(d.device, m_image, &requirements);
    VkMemoryAllocateInfo allocate{};
    allocate.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
    allocate.allocationSize = requirements.size;
    allocate.memoryTypeIndex =
        d.memory_type(requirements.memoryTypeBits, 0, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, "StorageImage");
    check(vkAllocateMemory(d.device, &allocate, nullptr, &m_memory), "vkAllocateMemory");
    check(vkBindImageMemory(d.device, m_image, m_memory, 0), "vkBindImageMemory");

    VkImageViewCreateInfo view{};

    view.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
    view.image = m_image;
    view.viewType = VK_IMAGE_VIEW_TYPE_2D;
    view.format = format;
    view.subresourceRange = kColor;
    check(vkCreateImageView(d.device, &view, nullptr, &m_view), "vkCreateImageView");

    // UNDEFINED -> GENERAL once, here: storage images are accessed in
    // GENERAL, which is the layout between commands from now on (download()
    // leaves it only for its copy). Nothing came before: no source access.
    d.submit_and_wait([&](VkCommandBuffer commands) {
      image_barrier(commands, m_image, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0,
                    VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                    VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_READ_BIT,
                    VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
    });
  } catch (...) {
    release();
    throw;
  }
}

StorageImage::~StorageImage() { release(); }

StorageImage::StorageImage(StorageImage&& other) noexcept
    : m_owner(std::exchange(other.m_owner, nullptr)),
      m_image(std::exchange(other.m_image, VK_NULL_HANDLE)),
      m_memory(std::exchange(other.m_memory, VK_NULL_HANDLE)),
      m_view(std::exchange(other.m_view, VK_NULL_HANDLE)),
      m_width(std::exchange(other.m_width, 0)),
      m_height(std::exchange(other.m_height, 0)),
      m_format(std::exchange(other.m_format, VK_FORMAT_UNDEFINED)),
      m_id(std::exchange(other.m_id, 0)) {}

StorageImage& StorageImage::operator=(StorageImage&& other) noexcept {
  if (this != &other) {
    release();
    m_owner = std::exchange(other.m_owner, nullptr);
    m_image = std::exchange(other.m_image, VK_NULL_HANDLE);
    m_memory = std::exchange(other.m_memory, VK_NULL_HANDLE);
    m_view = std::exchange(other.m_view, VK_NULL_HANDLE);
    m_width = std::exchange(other.m_width, 0);
    m_height = std::exchange(other.m_height, 0);
    m_format = std::exchange(other.m_format, VK_FORMAT_UNDEFINED);
    m_id = std::exchange(other.m_id, 0);
  }
  return *this;
}

void StorageImage::release() noexcept {
  if (m_owner == nullptr) return;
  const VkDevice device = m_owner->device;
  if (m_view != VK_NULL_HANDLE) vkDestroyImageView(device, m_view, nullptr);
  if (m_image != VK_NULL_HANDLE) vkDestroyImage(device, m_image, nullptr);
  if (m_memory != VK_NULL_HANDLE) vkFreeMemory(device, m_memory, nullptr);
  m_view = VK_NULL_HANDLE;
  m_image = VK_NULL_HANDLE;
  m_memory = VK_NULL_HANDLE;
  m_owner = nullptr;
}

std::uint32_t StorageImage::float_channels() const { return float_channels_of(m_format); }

std::vector<float> StorageImage::download() const {
  if (m_owner == nullptr) throw std::logic_error("StorageImage::download: the image was moved from");
  const std::uint32_t channels = float_channels();
  if (channels == 0) {
    throw std::logic_error("StorageImage::download: " + format_name(m_format) + " is not a 32-bit float format");
  }
  std::vector<float> pixels(std::size_t{m_width} * m_height * channels);
  copy_to_host(std::as_writable_bytes(std::span(pixels)));
  return pixels;
}

std::vector<std::uint8_t> StorageImage::download_bytes() const {
  if (m_owner == nullptr) throw std::logic_error("StorageImage::download_bytes: the image was moved from");
  if (m_format != VK_FORMAT_R8G8B8A8_UNORM && m_format != VK_FORMAT_B8G8R8A8_UNORM) {
    throw std::logic_error("StorageImage::download_bytes: " + format_name(m_format) + " is not an 8-bit RGBA/BGRA format");
  }
  std::vector<std::uint8_t> bytes(std::size_t{m_width} * m_height * 4);
  copy_to_host(std::as_writable_bytes(std::span(bytes)));
  return bytes;
}

void StorageImage::copy_to_host(std::span<std::byte> out) const {
  const std::size_t row_bytes = out.size() / m_height;
  copy_bands(row_bytes / m_width, 0, m_height, [&](std::uint32_t y, std::uint32_t, std::span<const std::byte> bytes) {
    std::copy(bytes.begin(), bytes.end(), out.begin() + static_cast<std::ptrdiff_t>(row_bytes * y));
  });
}

void StorageImage::download_rows(
    const std::function<void(std::uint32_t first_row, std::uint32_t rows, std::span<const float> values)>& band,
    std::uint32_t first, std::uint32_t count) const {
  if (m_owner == nullptr) throw std::logic_error("StorageImage::download_rows: the image was moved from");
  const std::uint32_t channels = float_channels();
  if (channels == 0) {
    throw std::logic_error("StorageImage::download_rows: " + format_name(m_format) + " is not a 32-bit float format");
  }
  if (count == 0 && first < m_height) count = m_height - first;
  if (first >= m_height || count > m_height - first) {
    throw std::out_of_range("StorageImage::download_rows: rows " + std::to_string(first) + " + " + std::to_string(count) +
                            " outside the image's " + std::to_string(m_height));
  }
  copy_bands(channels * sizeof(float), first, count, [&](std::uint32_t y, std::uint32_t rows, std::span<const std::byte> bytes) {
    band(y, rows, std::span(reinterpret_cast<const float*>(bytes.data()), bytes.size() / sizeof(float)));
  });
}

void StorageImage::copy_bands(
    std::size_t texel_bytes, std::uint32_t first, std::uint32_t count,
    const std::function<void(std::uint32_t, std::uint32_t, std::span<const std::byte>)>& band) const {
  // Band by band through a staging buffer of at most kStagingBytes (a row
  // at least), so that a large image costs the host no second copy of itself.
  constexpr std::size_t kStagingBytes = std::size_t{16} << 20;
  const std::size_t row_bytes = texel_bytes * m_width;
  const std::uint32_t band_rows = static_cast<std::uint32_t>(std::clamp<std::size_t>(kStagingBytes / row_bytes, 1, count));
  Buffer staging(m_owner, row_bytes * band_rows, BufferUsage::Storage);
  for (std::uint32_t y = first; y < first + count; y += band_rows) {
    const std::uint32_t rows = std::min(band_rows, first + count - y);
    m_owner->submit_and_wait([&](VkCommandBuffer commands) {
      // GENERAL -> TRANSFER_SRC_OPTIMAL for the copy; earlier dispatches' image
      // writes must land before the copy reads them.
      image_barrier(commands, m_image, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                    VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT, VK_IMAGE_LAYOUT_GENERAL,
                    VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);

      VkBufferImageCopy region{};
      region.bufferOffset = 0;
      region.bufferRowLength = 0;  // tightly packed
      region.bufferImageHeight = 0;
      region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
      region.imageOffset = {0, static_cast<std::int32_t>(y), 0};
      region.imageExtent = {m_width, rows, 1};
      vkCmdCopyImageToBuffer(commands, m_image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging.handle(), 1, &region);

      // Back to GENERAL for later dispatches, after the copy has read the image
      // (a write-after-read hazard: an execution dependency suffices).
      image_barrier(commands, m_image, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                    VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                    VK_IMAGE_LAYOUT_GENERAL);

      // The copy's writes must be visible to the host before it reads the mapping.
      VkBufferMemoryBarrier buffer_barrier{};
      buffer_barrier.sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER;
      buffer_barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
      buffer_barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
      buffer_barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
      buffer_barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
      buffer_barrier.buffer = staging.handle();
      buffer_barrier.offset = 0;
      buffer_barrier.size = VK_WHOLE_SIZE;
      vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0, nullptr, 1,
                           &buffer_barrier, 0, nullptr);
    });
    band(y, rows, std::span<const std::byte>(staging.bytes().data(), row_bytes * rows));
  }
}

void image_barrier(VkCommandBuffer commands, VkImage image, VkPipelineStageFlags src_stage, VkAccessFlags src_access,
                   VkPipelineStageFlags dst_stage, VkAccessFlags dst_access, VkImageLayout from, VkImageLayout to) {
  VkImageMemoryBarrier barrier{};
  barrier.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
  barrier.srcAccessMask = src_access;
  barrier.dstAccessMask = dst_access;
  barrier.oldLayout = from;
  barrier.newLayout = to;
  barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.image = image;
  barrier.subresourceRange = kColor;
  vkCmdPipelineBarrier(commands, src_stage, dst_stage, 0, 0, nullptr, 0, nullptr, 1, &barrier);
}

}  // namespace sol::vk
