#include "sol/vk/buffer.hpp"

#include <atomic>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>

#include "device.hpp"
#include "sol/vk/context.hpp"
#include "sol/vk/error.hpp"

namespace sol::vk {
namespace {

void check_range(VkDeviceSize offset, std::size_t count, VkDeviceSize size, const char* what) {
  if (offset > size || count > size - offset) {
    throw std::out_of_range(std::string("Buffer::") + what + ": bytes [" + std::to_string(offset) + ", " +
                            std::to_string(offset + count) + ") outside the buffer's " + std::to_string(size));
  }
}

}  // namespace

std::uint64_t detail::next_resource_id() {
  static std::atomic<std::uint64_t> next{1};
  return next.fetch_add(1, std::memory_order_relaxed);
}

Buffer::Buffer(Context& context, VkDeviceSize size, BufferUsage usage) : Buffer(context.internals(), size, usage) {}

Buffer::Buffer(std::shared_ptr<detail::Device> owner, VkDeviceSize size, BufferUsage usage)
    : m_owner(std::move(owner)), m_size(size), m_usage(usage), m_id(detail::next_resource_id()) {
  if (size == 0) throw std::invalid_argument("Buffer: size must be positive");
  const detail::Device& device = *m_owner;
  const VkDevice vk_device = device.device;
  try {
    VkBufferCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
    info.size = size;
    // Transfers both ways too, so that images can be copied in and out.
    // Storage buffers may hold indirect dispatch arguments.
    info.usage = (usage == BufferUsage::Uniform ? VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT
                                                : VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT) |
                 VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    check(vkCreateBuffer(vk_device, &info, nullptr, &m_buffer), "vkCreateBuffer");

    VkMemoryRequirements requirements{};
    vkGetBufferMemoryRequirements(vk_device, m_buffer, &requirements);
    VkMemoryAllocateInfo allocate{};
    allocate.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
    allocate.allocationSize = requirements.size;
    // Every device has a host-visible, host-coherent type (the spec requires
    // one); cached memory makes reading results back fast.
    // (The device's own buffers: device-local memory where there is any.)
    const bool mapped_memory = usage != BufferUsage::DeviceStorage;
    allocate.memoryTypeIndex =
        mapped_memory ? device.memory_type(requirements.memoryTypeBits,
                                           VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT,
                                           VK_MEMORY_PROPERTY_HOST_CACHED_BIT, "Buffer")
                      : device.memory_type(requirements.memoryTypeBits, 0, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, "Buffer");
    check(vkAllocateMemory(vk_device, &allocate, nullptr, &m_memory), "vkAllocateMemory");
    check(vkBindBufferMemory(vk_device, m_buffer, m_memory, 0), "vkBindBufferMemory");
    if (!mapped_memory) return;
    void* mapped = nullptr;
    check(vkMapMemory(vk_device, m_memory, 0, VK_WHOLE_SIZE, 0, &mapped), "vkMapMemory");
    m_mapped = static_cast<std::byte*>(mapped);
    std::memset(m_mapped, 0, static_cast<std::size_t>(m_size));
  } catch (...) {
    release();
    throw;
  }
}

Buffer::~Buffer() { release(); }

Buffer::Buffer(Buffer&& other) noexcept
    : m_owner(std::exchange(other.m_owner, nullptr)),
      m_buffer(std::exchange(other.m_buffer, VK_NULL_HANDLE)),
      m_memory(std::exchange(other.m_memory, VK_NULL_HANDLE)),
      m_mapped(std::exchange(other.m_mapped, nullptr)),
      m_size(std::exchange(other.m_size, 0)),
      m_usage(other.m_usage),
      m_id(std::exchange(other.m_id, 0)) {}

Buffer& Buffer::operator=(Buffer&& other) noexcept {
  if (this != &other) {
    release();
    m_owner = std::exchange(other.m_owner, nullptr);
    m_buffer = std::exchange(other.m_buffer, VK_NULL_HANDLE);
    m_memory = std::exchange(other.m_memory, VK_NULL_HANDLE);
    m_mapped = std::exchange(other.m_mapped, nullptr);
    m_size = std::exchange(other.m_size, 0);
    m_usage = other.m_usage;
    m_id = std::exchange(other.m_id, 0);
  }
  return *this;
}

void Buffer::release() noexcept {
  if (m_owner == nullptr) return;
  const VkDevice device = m_owner->device;
  if (m_buffer != VK_NULL_HANDLE) vkDestroyBuffer(device, m_buffer, nullptr);
  if (m_memory != VK_NULL_HANDLE) vkFreeMemory(device, m_memory, nullptr);  // unmaps too
  m_buffer = VK_NULL_HANDLE;
  m_memory = VK_NULL_HANDLE;
  m_mapped = nullptr;
  m_size = 0;
  m_owner = nullptr;
}

void Buffer::write_bytes(std::span<const std::byte> data, VkDeviceSize offset) {
  if (m_usage == BufferUsage::DeviceStorage) throw std::logic_error("Buffer::write: a DeviceStorage buffer is not mapped");
  check_range(offset, data.size(), m_size, "write");
  if (!data.empty()) std::memcpy(m_mapped + offset, data.data(), data.size());
}

void Buffer::read_bytes(std::span<std::byte> data, VkDeviceSize offset) const {
  if (m_usage == BufferUsage::DeviceStorage) throw std::logic_error("Buffer::read: a DeviceStorage buffer is not mapped");
  check_range(offset, data.size(), m_size, "read");
  if (!data.empty()) std::memcpy(data.data(), m_mapped + offset, data.size());
}

}  // namespace sol::vk
