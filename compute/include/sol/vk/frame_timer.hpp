// Two device timestamps around a frame's commands, read once the frame is
// done: what presenters time their frames by (solview --stats, solxr
// --stats). One per frame in flight; each is reset by the commands that
// write it, so a command buffer may be recorded with it again once the
// frame before is done.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>

#include <vulkan/vulkan_core.h>

namespace sol::vk {

class Context;
namespace detail {
struct Device;
}

class FrameTimer {
 public:
  /// The frame's two timestamps, in ticks of the queue's clock (only the
  /// low timestampValidBits bits count: take differences with elapsed_ms).
  struct Reading {
    std::uint64_t begin = 0, end = 0;
  };

  /// A pool of two timestamp queries where the queue writes timestamps
  /// (Context::timestamps_supported); none otherwise, and then begin(),
  /// end() record nothing and read() gives nothing.
  explicit FrameTimer(Context& context);
  ~FrameTimer();
  FrameTimer(FrameTimer&& other) noexcept;
  FrameTimer& operator=(FrameTimer&& other) noexcept;
  FrameTimer(const FrameTimer&) = delete;
  FrameTimer& operator=(const FrameTimer&) = delete;

  bool supported() const { return m_pool != VK_NULL_HANDLE; }
  /// Records the reset and the first timestamp, before the frame's first command.
  void begin(VkCommandBuffer command_buffer) const;
  /// Records the second, after every command of the frame.
  void end(VkCommandBuffer command_buffer) const;
  /// The two timestamps once the frame's commands are done (waits for the
  /// results otherwise); std::nullopt without timestamps.
  std::optional<Reading> read() const;
  /// Milliseconds from tick `from` to a later tick `to` of the same queue
  /// (the unsigned difference under the valid bits: a wrap-around between
  /// them is taken into account).
  double elapsed_ms(std::uint64_t from, std::uint64_t to) const;

 private:
  void release() noexcept;
  std::shared_ptr<detail::Device> m_owner;
  VkQueryPool m_pool = VK_NULL_HANDLE;
};

}  // namespace sol::vk
