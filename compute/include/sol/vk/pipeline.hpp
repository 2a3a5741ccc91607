// A compute pipeline with its descriptor set, and the dispatch that runs it.
//
// One pipeline = one SPIR-V compute shader (entry point "main"), one
// descriptor set (set = 0) whose bindings are listed in the description, an
// optional push-constant block and specialisation constants (the tuning
// knobs: workgroup size, integrator, ...). Resources are bound by binding
// number; run() records and submits one dispatch and waits for it.
//
//   sol::vk::ComputePipeline fill(context, {.name = "fill",
//                                           .spirv = sol::vk::shaders::fill(),
//                                           .bindings = {{0, sol::vk::DescriptorType::StorageImage}},
//                                           .push_constant_size = sizeof(float)});
//   fill.bind(0, image);
//   double ms = fill.run(sol::vk::group_count(width, 8), sol::vk::group_count(height, 8), 0.5f);
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <ranges>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include <vulkan/vulkan_core.h>

namespace sol::vk {

class Buffer;
class Context;
class StorageImage;
namespace detail {
struct Device;
}

enum class DescriptorType { StorageImage, StorageBuffer, UniformBuffer };

struct Binding {
  std::uint32_t binding = 0;
  DescriptorType type = DescriptorType::StorageImage;
};

/// A specialisation constant: `layout(constant_id = id)`. Every scalar
/// constant is 32 bits: store an int or uint as it is, a bool as 0 or 1, a
/// float as std::bit_cast<std::uint32_t>(x).
struct SpecializationConstant {
  std::uint32_t id = 0;
  std::uint32_t value = 0;
};

/// Where a pipeline's specialisation constants are applied. The same
/// program either way; what differs is the build time and, on a GPU, the
/// code its compiler makes of it (docs/renderer.md, "The kernel's interface").
enum class SpecializationFolding {
  /// Folded on a CPU device (VK_PHYSICAL_DEVICE_TYPE_CPU: lavapipe, whose
  /// front end inlines every function before it drops the branches the
  /// constants rule out, builds the march kernel's variants 5-9x faster
  /// folded), handed to the driver elsewhere (an NVIDIA driver builds them
  /// faster itself, and its code for some variants was faster unfolded).
  Auto,
  /// Folded into the SPIR-V before the driver sees it (specialize_spirv).
  Folded,
  /// Handed to the driver (VkSpecializationInfo), as Vulkan does.
  Driver,
};

// Members have default initialisers so that designated initialisers may leave
// any out without -Wmissing-field-initializers.
struct ComputePipelineDesc {
  /// Names the pipeline in error messages.
  std::string name{};
  /// The SPIR-V words; validated with SPIRV-Tools before the driver sees them.
  std::span<const std::uint32_t> spirv{};
  /// Whether the words passed validation already (the project's kernels:
  /// glslangValidator --spirv-val at build time): they are not validated
  /// again, a second or more per kernel on lavapipe's first frame; folded
  /// words still are. Words not known valid must leave it false (the
  /// folding passes may fail on invalid ones in ways no check catches).
  bool validated = false;
  std::vector<Binding> bindings{};
  /// Bytes of the push-constant block (a multiple of 4, at most the device's
  /// maxPushConstantsSize; 0 for none).
  std::uint32_t push_constant_size = 0;
  std::vector<SpecializationConstant> specialization{};
  /// How the specialisation constants reach the code (SpecializationFolding).
  SpecializationFolding specialization_folding = SpecializationFolding::Auto;
  /// Descriptor sets, each with every binding (at least 1). A caller with
  /// several frames in flight binds each frame's resources into a set that
  /// no pending command buffer uses (a set must not be updated while a
  /// command buffer that uses it is pending or being recorded).
  std::uint32_t descriptor_sets = 1;
};

/// The module with its specialisation constants given their values and
/// frozen into constants, and the code those values rule out removed
/// (SPIRV-Tools: frozen default values, folded constant expressions,
/// conditional constant propagation (a guard `HAS_X && runtime` is an
/// OpLogicalAnd that only propagation folds), dead branches, dead
/// functions, aggressive dead-code elimination; no inlining or other
/// rewriting: inlined modules with merged returns were smaller, but
/// lavapipe built them no faster). Constants the module does not declare are ignored, as
/// Vulkan ignores them. Throws VulkanError where the words are not valid
/// SPIR-V (unless `validated`: known valid, ComputePipelineDesc::validated)
/// or the result does not validate.
std::vector<std::uint32_t> specialize_spirv(std::span<const std::uint32_t> words,
                                            std::span<const SpecializationConstant> constants,
                                            const std::string& pipeline = "unnamed", bool validated = false);

/// Where pipelines keep their folded modules between runs: $SOL_SPIRV_CACHE
/// (a directory; "off" or empty: none), else $XDG_CACHE_HOME/sol/spirv,
/// else $HOME/.cache/sol/spirv; none where neither is set.
std::optional<std::filesystem::path> spirv_cache_directory();

/// The largest cache file read back (a folded kernel is about a megabyte,
/// the connection seeds' table 400 KB): anything larger is passed over.
inline constexpr std::uintmax_t kMaxCacheFileBytes = std::uintmax_t{64} << 20;

/// A cache file's contents: the key of what it holds (which the reader
/// compares with the key it asks for) and its body.
struct CacheFile {
  std::uint64_t key = 0;
  std::vector<std::uint32_t> words;
};
/// A cache file written by write_cache_file, read back: a header (the
/// magic "SOLC", the format, the key, the body's length and a 64-bit
/// FNV-1a checksum of it), then the body in 32-bit words. None where the
/// file is not a regular file of at most kMaxCacheFileBytes (a FIFO or a
/// device is never waited on; sol::read_regular_file), cannot be read, or
/// its header, length or checksum do not hold: a truncated, zeroed or
/// foreign file is passed over (and the caller writes it again).
std::optional<CacheFile> read_cache_file(const std::filesystem::path& file);
/// Writes `words` with `key` to a cache file whole or not at all: to a
/// temporary name in the same directory (created if need be), closed and
/// checked, then renamed into place, so that processes writing at once
/// never leave or read a partial file. A failure is silent (the caller
/// computes again).
void write_cache_file(const std::filesystem::path& file, std::uint64_t key, std::span<const std::uint32_t> words);
/// The key of specialize_spirv_cached's file for these words and
/// constants (sorted by id): a 64-bit FNV-1a hash, which names the file too.
std::uint64_t spirv_cache_key(std::span<const std::uint32_t> words, std::span<const SpecializationConstant> constants);

/// specialize_spirv, kept in `directory` (none: folded every time): a cache
/// file named by spirv_cache_key and holding it (a module another variant
/// folded, copied under this name, is passed over), the folded module as it
/// was made. A module folded before is read
/// back and validated instead of folded again (folding the march kernel
/// takes about a second; reading it, milliseconds); a new one is written
/// to a temporary file and renamed into place, so that processes folding
/// at once never read a partial file. A cache that cannot be read or
/// written, or holds a file that does not validate, is passed over: the
/// module is folded (and the file written again).
std::vector<std::uint32_t> specialize_spirv_cached(std::span<const std::uint32_t> words,
                                                   std::span<const SpecializationConstant> constants,
                                                   const std::string& pipeline,
                                                   const std::optional<std::filesystem::path>& directory,
                                                   bool validated = false);

/// Workgroups needed to cover `extent` invocations with groups of `local_size`.
constexpr std::uint32_t group_count(std::uint32_t extent, std::uint32_t local_size) {
  return extent / local_size + (extent % local_size != 0 ? 1u : 0u);
}

/// A push-constant block passed by value: a trivially copyable struct or
/// scalar (not a pointer, span or other range, which would copy the wrong bytes).
template <class T>
concept PushConstantBlock =
    std::is_trivially_copyable_v<T> && !std::is_pointer_v<T> && !std::ranges::range<T>;

class ComputePipeline {
 public:
  /// Throws VulkanError for SPIR-V that does not validate or that the driver
  /// rejects, std::invalid_argument for a bad description (duplicate binding,
  /// push-constant size).
  ComputePipeline(Context& context, const ComputePipelineDesc& desc);
  ~ComputePipeline();
  ComputePipeline(ComputePipeline&& other) noexcept;
  ComputePipeline& operator=(ComputePipeline&& other) noexcept;
  ComputePipeline(const ComputePipeline&) = delete;
  ComputePipeline& operator=(const ComputePipeline&) = delete;

  /// Binds a resource to `binding` of descriptor set `set`: a StorageImage
  /// to a StorageImage binding, a Storage buffer to a StorageBuffer binding,
  /// a Uniform buffer to a UniformBuffer binding. Anything else, or a set
  /// beyond descriptor_sets(), throws std::invalid_argument. The resource
  /// must outlive its use by run(). Not while a dispatch that uses the set
  /// is pending or being recorded.
  void bind(std::uint32_t binding, const StorageImage& image, std::uint32_t set = 0);
  void bind(std::uint32_t binding, const Buffer& buffer, std::uint32_t set = 0);
  /// Binds an image view of the caller's (a swapchain image's, say) to a
  /// StorageImage binding; the image must have STORAGE usage and be in
  /// GENERAL layout when a dispatch runs. Throws std::invalid_argument for a
  /// null view or a binding of another type.
  void bind(std::uint32_t binding, VkImageView storage_view, std::uint32_t set = 0);

  /// Dispatches groups_x × groups_y × 1 workgroups and waits for them; returns
  /// the time the device took in milliseconds (see Context::submit_and_wait).
  /// Shader writes are visible to the host and to later dispatches when it
  /// returns. Throws std::logic_error when a binding has nothing bound,
  /// std::invalid_argument when the push constants do not have
  /// push_constant_size bytes or a group count is 0 or over the device limit.
  double run(std::uint32_t groups_x, std::uint32_t groups_y,
             std::span<const std::byte> push_constants = {});
  template <PushConstantBlock T>
  double run(std::uint32_t groups_x, std::uint32_t groups_y, const T& push_constants) {
    return run(groups_x, groups_y, std::as_bytes(std::span(&push_constants, 1)));
  }

  /// Records the dispatch alone (bind pipeline and descriptor set `set`,
  /// push constants, vkCmdDispatch) into a command buffer of the caller, who
  /// provides the barriers around it. Same checks as run(), for that set.
  void record_dispatch(VkCommandBuffer command_buffer, std::uint32_t groups_x, std::uint32_t groups_y,
                       std::span<const std::byte> push_constants = {}, std::uint32_t set = 0) const;

  /// The same with the workgroup counts read by the device from `arguments`
  /// at byte `offset` (a VkDispatchIndirectCommand, written by an earlier
  /// dispatch: the caller's barrier makes it visible to
  /// VK_ACCESS_INDIRECT_COMMAND_READ_BIT). Throws std::logic_error when a
  /// binding has nothing bound, std::invalid_argument when the command lies
  /// outside the buffer or `offset` is not a multiple of 4.
  void record_dispatch_indirect(VkCommandBuffer command_buffer, const Buffer& arguments, VkDeviceSize offset,
                                std::span<const std::byte> push_constants = {}, std::uint32_t set = 0) const;

  const std::string& name() const { return m_name; }
  VkPipeline handle() const { return m_pipeline; }
  VkPipelineLayout layout() const { return m_layout; }
  VkDescriptorSet descriptor_set(std::uint32_t set = 0) const { return m_sets.at(set); }
  std::uint32_t descriptor_sets() const { return static_cast<std::uint32_t>(m_sets.size()); }

 private:
  const Binding& find_binding(std::uint32_t binding, DescriptorType type, std::uint32_t set) const;
  void write(const Binding& binding, std::uint32_t set, const VkWriteDescriptorSet& write);
  void check_dispatch(std::uint32_t groups_x, std::uint32_t groups_y, std::span<const std::byte> push_constants,
                      std::uint32_t set) const;
  // Binds the pipeline, the set and the push constants for a dispatch.
  void record_state(VkCommandBuffer command_buffer, std::span<const std::byte> push_constants, std::uint32_t set) const;
  void release() noexcept;

  std::shared_ptr<detail::Device> m_owner;
  std::string m_name;
  std::vector<Binding> m_bindings;
  std::vector<bool> m_bound;  // set s's binding i at s · bindings + i
  std::uint32_t m_push_constant_size = 0;
  VkDescriptorSetLayout m_set_layout = VK_NULL_HANDLE;
  VkPipelineLayout m_layout = VK_NULL_HANDLE;
  VkPipeline m_pipeline = VK_NULL_HANDLE;
  VkDescriptorPool m_pool = VK_NULL_HANDLE;
  std::vector<VkDescriptorSet> m_sets;
};

/// Records a global memory barrier: what `src_access` wrote in `src_stages`
/// completes and becomes visible to `dst_access` in `dst_stages` (and
/// `src_stages` finish before `dst_stages` start).
void record_memory_barrier(VkCommandBuffer command_buffer, VkPipelineStageFlags src_stages, VkAccessFlags src_access,
                           VkPipelineStageFlags dst_stages, VkAccessFlags dst_access);

/// Several dispatches in one submission, as run() submits one: `record`
/// records them (with the barriers between them) and is placed between
/// run()'s barriers (earlier shader writes and copies complete first; the
/// shader writes are visible to the host after); waits, and returns the
/// device's time in milliseconds (see Context::submit_and_wait).
double run_recorded(Context& context, const std::function<void(VkCommandBuffer)>& record);

}  // namespace sol::vk
