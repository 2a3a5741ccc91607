// A host-visible buffer for shaders to read or write.
//
// The memory is host-visible and host-coherent and stays mapped for the
// buffer's lifetime: write() before a dispatch and read() after it need no
// flushes. ComputePipeline::run makes shader writes visible to the host
// before it returns.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <ranges>
#include <span>
#include <type_traits>

#include <vulkan/vulkan_core.h>

namespace sol::vk {

class Context;
class StorageImage;
namespace detail {
struct Device;
}

/// How shaders see the buffer: a `buffer` block (std430) or a `uniform`
/// block (std140). DeviceStorage is a `buffer` block that only the device
/// reads and writes (a kernel's scratch lists, indirect dispatch arguments):
/// in device-local memory where the device has it, never mapped (bytes() is
/// empty; write() and read() throw std::logic_error).
enum class BufferUsage { Storage, Uniform, DeviceStorage };

/// A contiguous range of trivially copyable values (std::vector<float>,
/// std::array, std::span, ...).
template <class R>
concept TrivialRange = std::ranges::contiguous_range<R> && std::ranges::sized_range<R> &&
                       std::is_trivially_copyable_v<std::ranges::range_value_t<R>>;

class Buffer {
 public:
  /// `size` bytes (> 0), zero-initialised.
  Buffer(Context& context, VkDeviceSize size, BufferUsage usage = BufferUsage::Storage);
  ~Buffer();
  Buffer(Buffer&& other) noexcept;
  Buffer& operator=(Buffer&& other) noexcept;
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;

  VkBuffer handle() const { return m_buffer; }
  VkDeviceSize size() const { return m_size; }
  BufferUsage usage() const { return m_usage; }
  /// This buffer's identity: unique among the process's buffers and images,
  /// never reused (a handle may be, once its object is destroyed); 0 after
  /// a move from it.
  std::uint64_t id() const { return m_id; }

  /// The mapped memory.
  std::span<std::byte> bytes() { return {m_mapped, m_mapped ? static_cast<std::size_t>(m_size) : 0u}; }
  std::span<const std::byte> bytes() const { return {m_mapped, m_mapped ? static_cast<std::size_t>(m_size) : 0u}; }

  /// Copies `data` to byte `offset`; throws std::out_of_range past the end.
  void write_bytes(std::span<const std::byte> data, VkDeviceSize offset = 0);
  /// Copies from byte `offset` into `data`; throws std::out_of_range past the end.
  void read_bytes(std::span<std::byte> data, VkDeviceSize offset = 0) const;

  template <TrivialRange R>
  void write(const R& values, VkDeviceSize offset = 0) {
    write_bytes(std::as_bytes(std::span(values)), offset);
  }
  template <TrivialRange R>
  void read(R&& values, VkDeviceSize offset = 0) const {
    read_bytes(std::as_writable_bytes(std::span(values)), offset);
  }

 private:
  friend class StorageImage;  // its download() stages through a Buffer
  Buffer(std::shared_ptr<detail::Device> owner, VkDeviceSize size, BufferUsage usage);
  void release() noexcept;

  std::shared_ptr<detail::Device> m_owner;
  VkBuffer m_buffer = VK_NULL_HANDLE;
  VkDeviceMemory m_memory = VK_NULL_HANDLE;
  std::byte* m_mapped = nullptr;
  VkDeviceSize m_size = 0;
  BufferUsage m_usage = BufferUsage::Storage;
  std::uint64_t m_id = 0;
};

}  // namespace sol::vk
