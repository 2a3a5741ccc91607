#include "sol/vk/frame_timer.hpp"

#include <utility>

#include "device.hpp"
#include "sol/vk/context.hpp"
#include "sol/vk/error.hpp"

namespace sol::vk {

FrameTimer::FrameTimer(Context& context) : m_owner(context.internals()) {
  if (!context.timestamps_supported()) return;
  VkQueryPoolCreateInfo queries{};
  queries.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO;
  queries.queryType = VK_QUERY_TYPE_TIMESTAMP;
  queries.queryCount = 2;
  check(vkCreateQueryPool(m_owner->device, &queries, nullptr, &m_pool), "vkCreateQueryPool");
}

FrameTimer::~FrameTimer() { release(); }

FrameTimer::FrameTimer(FrameTimer&& other) noexcept
    : m_owner(std::move(other.m_owner)), m_pool(std::exchange(other.m_pool, VK_NULL_HANDLE)) {}

FrameTimer& FrameTimer::operator=(FrameTimer&& other) noexcept {
  if (this != &other) {
    release();
    m_owner = std::move(other.m_owner);
    m_pool = std::exchange(other.m_pool, VK_NULL_HANDLE);
  }
  return *this;
}

void FrameTimer::release() noexcept {
  if (m_pool != VK_NULL_HANDLE && m_owner) vkDestroyQueryPool(m_owner->device, m_pool, nullptr);
  m_pool = VK_NULL_HANDLE;
}

void FrameTimer::begin(VkCommandBuffer command_buffer) const {
  if (m_pool == VK_NULL_HANDLE) return;
  vkCmdResetQueryPool(command_buffer, m_pool, 0, 2);
  vkCmdWriteTimestamp(command_buffer, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, m_pool, 0);
}

void FrameTimer::end(VkCommandBuffer command_buffer) const {
  if (m_pool != VK_NULL_HANDLE) vkCmdWriteTimestamp(command_buffer, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, m_pool, 1);
}

std::optional<FrameTimer::Reading> FrameTimer::read() const {
  if (m_pool == VK_NULL_HANDLE) return std::nullopt;
  std::uint64_t ticks[2] = {0, 0};
  check(vkGetQueryPoolResults(m_owner->device, m_pool, 0, 2, sizeof ticks, ticks, sizeof(std::uint64_t),
                              VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
        "vkGetQueryPoolResults");
  return Reading{ticks[0], ticks[1]};
}

double FrameTimer::elapsed_ms(std::uint64_t from, std::uint64_t to) const { return m_owner->elapsed_ms(from, to); }

}  // namespace sol::vk
