#include "sol/vk/pipeline.hpp"

#include <algorithm>
#include <cstring>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <random>
#include <system_error>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <spirv-tools/libspirv.hpp>
#include <spirv-tools/optimizer.hpp>

#include <sol/file_io.hpp>

#include "device.hpp"
#include "fnv1a.hpp"
#include "sol/vk/buffer.hpp"
#include "sol/vk/context.hpp"
#include "sol/vk/error.hpp"
#include "sol/vk/image.hpp"

namespace sol::vk {
namespace {

const char* type_name(DescriptorType type) {
  switch (type) {
    case DescriptorType::StorageImage: return "storage image";
    case DescriptorType::StorageBuffer: return "storage buffer";
    default: return "uniform buffer";
  }
}

VkDescriptorType vk_type(DescriptorType type) {
  switch (type) {
    case DescriptorType::StorageImage: return VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    case DescriptorType::StorageBuffer: return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    default: return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  }
}

/// Whether the module declares `OpEntryPoint GLCompute %id "main"`. The
/// words are valid SPIR-V already: a header of five words, then instructions
/// whose first word holds (word count << 16) | opcode.
bool has_compute_main(std::span<const std::uint32_t> words) {
  constexpr std::uint32_t kOpEntryPoint = 15;
  constexpr std::uint32_t kGLCompute = 5;
  for (std::size_t at = 5; at < words.size();) {
    const std::uint32_t count = words[at] >> 16;
    const std::uint32_t opcode = words[at] & 0xffffu;
    if (count == 0 || at + count > words.size()) return false;
    if (opcode == kOpEntryPoint && count >= 4 && words[at + 1] == kGLCompute) {
      // The name: a nul-terminated string packed little-endian into words.
      std::string name;
      for (std::size_t w = at + 3; w < at + count && name.size() == 4 * (w - at - 3); ++w) {
        for (int byte = 0; byte < 4; ++byte) {
          const char ch = static_cast<char>((words[w] >> (8 * byte)) & 0xffu);
          if (ch == '\0') break;
          name.push_back(ch);
        }
      }
      if (name == "main") return true;
    }
    at += count;
  }
  return false;
}

/// Drivers are not required to survive invalid SPIR-V (and some do not), so
/// it is checked here, with the validator glslang uses, before any driver sees it.
void validate_spirv(std::span<const std::uint32_t> words, const std::string& pipeline) {
  const std::string prefix = "pipeline '" + pipeline + "': invalid SPIR-V (not passed to vkCreateShaderModule): ";
  if (words.empty()) throw VulkanError(VK_ERROR_UNKNOWN, prefix + "no code");
  std::string diagnostics;
  spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_2);
  tools.SetMessageConsumer([&](spv_message_level_t, const char*, const spv_position_t& position, const char* message) {
    if (!diagnostics.empty()) diagnostics += "; ";
    diagnostics += message;
    diagnostics += " (word " + std::to_string(position.index) + ")";
  });
  if (!tools.Validate(words.data(), words.size())) {
    throw VulkanError(VK_ERROR_UNKNOWN,
                      prefix + (diagnostics.empty() ? std::string("rejected by the validator") : diagnostics));
  }
  if (!has_compute_main(words)) throw VulkanError(VK_ERROR_UNKNOWN, prefix + "no GLCompute entry point 'main'");
}

}  // namespace

std::vector<std::uint32_t> specialize_spirv(std::span<const std::uint32_t> words,
                                            std::span<const SpecializationConstant> constants,
                                            const std::string& pipeline, bool validated) {
  if (!validated) validate_spirv(words, pipeline);
  std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> values;
  for (const SpecializationConstant& c : constants) values[c.id] = {c.value};
  std::string diagnostics;
  spvtools::Optimizer optimizer(SPV_ENV_VULKAN_1_2);
  optimizer.SetMessageConsumer([&](spv_message_level_t level, const char*, const spv_position_t&, const char* message) {
    if (level > SPV_MSG_WARNING) return;
    if (!diagnostics.empty()) diagnostics += "; ";
    diagnostics += message;
  });
  optimizer.RegisterPass(spvtools::CreateSetSpecConstantDefaultValuePass(values))
      .RegisterPass(spvtools::CreateFreezeSpecConstantValuePass())
      .RegisterPass(spvtools::CreateFoldSpecConstantOpAndCompositePass())
      .RegisterPass(spvtools::CreateCCPPass())  // `HAS_X && runtime` guards: OpLogicalAnd with a constant
      .RegisterPass(spvtools::CreateDeadBranchElimPass())
      .RegisterPass(spvtools::CreateEliminateDeadFunctionsPass())
      .RegisterPass(spvtools::CreateAggressiveDCEPass());
  spvtools::OptimizerOptions options;
  options.set_run_validator(false);  // validated above
  std::vector<std::uint32_t> folded;
  if (!optimizer.Run(words.data(), words.size(), &folded, options)) {
    throw VulkanError(VK_ERROR_UNKNOWN, "pipeline '" + pipeline + "': its specialisation constants could not be folded" +
                                            (diagnostics.empty() ? std::string() : ": " + diagnostics));
  }
  validate_spirv(folded, pipeline + " (specialised)");
  return folded;
}

std::optional<std::filesystem::path> spirv_cache_directory() {
  if (const char* own = std::getenv("SOL_SPIRV_CACHE")) {
    const std::string value(own);
    if (value.empty() || value == "off") return std::nullopt;
    return std::filesystem::path(value);
  }
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::filesystem::path(xdg) / "sol" / "spirv";
  if (const char* home = std::getenv("HOME"); home && *home) return std::filesystem::path(home) / ".cache" / "sol" / "spirv";
  return std::nullopt;
}

namespace {

using detail::fnv1a;

// A cache file's header, before its body (words, little-endian as written).
constexpr std::uint32_t kCacheMagic = 0x434c4f53u;  // "SOLC"
// Raised whenever specialize_spirv's passes change: a module folded by
// other passes is then folded again (the key holds only the module and the
// constants).
constexpr std::uint32_t kCacheFormat = 2;
constexpr std::size_t kCacheHeaderWords = 7;  // magic, format, key (2), body words, checksum (2)

std::uint64_t checksum(std::span<const std::uint32_t> words) {
  std::uint64_t hash = detail::kFnvOffset;
  for (std::uint32_t w : words) hash = fnv1a(hash, w);
  return hash;
}

}  // namespace

std::uint64_t spirv_cache_key(std::span<const std::uint32_t> words, std::span<const SpecializationConstant> constants) {
  std::vector<SpecializationConstant> sorted(constants.begin(), constants.end());
  std::sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return a.id < b.id; });
  std::uint64_t hash = checksum(words);
  for (const SpecializationConstant& c : sorted) hash = fnv1a(fnv1a(hash, c.id), c.value);
  return hash;
}

std::optional<CacheFile> read_cache_file(const std::filesystem::path& file) {
  const std::optional<std::string> bytes = read_regular_file(file, kMaxCacheFileBytes);
  if (!bytes || bytes->size() % 4 != 0 || bytes->size() < 4 * kCacheHeaderWords) return std::nullopt;
  std::vector<std::uint32_t> words(bytes->size() / 4);
  std::memcpy(words.data(), bytes->data(), bytes->size());
  auto u64 = [&](std::size_t at) { return static_cast<std::uint64_t>(words[at]) | static_cast<std::uint64_t>(words[at + 1]) << 32; };
  if (words[0] != kCacheMagic || words[1] != kCacheFormat || words[4] != words.size() - kCacheHeaderWords) return std::nullopt;
  CacheFile kept{u64(2), std::vector<std::uint32_t>(words.begin() + kCacheHeaderWords, words.end())};
  if (checksum(kept.words) != u64(5)) return std::nullopt;  // a body that is not the one written
  return kept;
}

void write_cache_file(const std::filesystem::path& file, std::uint64_t key, std::span<const std::uint32_t> words) {
  if (words.size() > kMaxCacheFileBytes / 4 - kCacheHeaderWords) return;  // (never read back)
  std::error_code error;
  std::filesystem::create_directories(file.parent_path(), error);
  if (error) return;
  const std::uint64_t sum = checksum(words);
  const std::uint32_t header[kCacheHeaderWords] = {kCacheMagic,
                                                   kCacheFormat,
                                                   static_cast<std::uint32_t>(key),
                                                   static_cast<std::uint32_t>(key >> 32),
                                                   static_cast<std::uint32_t>(words.size()),
                                                   static_cast<std::uint32_t>(sum),
                                                   static_cast<std::uint32_t>(sum >> 32)};
  std::random_device random;
  const std::filesystem::path partial = file.string() + ".partial-" + std::to_string(random());
  bool whole = false;
  {
    std::ofstream out(partial, std::ios::binary | std::ios::trunc);
    if (!out) return;
    out.write(reinterpret_cast<const char*>(header), sizeof header);
    out.write(reinterpret_cast<const char*>(words.data()), static_cast<std::streamsize>(words.size() * 4));
    out.close();
    whole = !out.fail();
  }
  if (whole) std::filesystem::rename(partial, file, error);
  if (!whole || error) std::filesystem::remove(partial, error);
}

std::vector<std::uint32_t> specialize_spirv_cached(std::span<const std::uint32_t> words,
                                                   std::span<const SpecializationConstant> constants,
                                                   const std::string& pipeline,
                                                   const std::optional<std::filesystem::path>& directory,
                                                   bool validated) {
  if (!directory) return specialize_spirv(words, constants, pipeline, validated);
  const std::uint64_t key = spirv_cache_key(words, constants);
  char name[64];
  std::snprintf(name, sizeof name, "%zu-%016llx.spv", words.size(), static_cast<unsigned long long>(key));
  const std::filesystem::path file = *directory / name;
  // Read back only where the file holds what was written for this key
  // (read_cache_file checks the body's checksum); then validated.
  if (std::optional<CacheFile> kept = read_cache_file(file); kept && kept->key == key) {
    try {
      validate_spirv(kept->words, pipeline + " (specialised, from " + file.string() + ")");
      return std::move(kept->words);
    } catch (const VulkanError&) {
      // not a module: folded again below, and the file replaced
    }
  }
  std::vector<std::uint32_t> folded = specialize_spirv(words, constants, pipeline, validated);
  write_cache_file(file, key, folded);
  return folded;
}

ComputePipeline::ComputePipeline(Context& context, const ComputePipelineDesc& desc)
    : m_owner(context.internals()),
      m_name(desc.name.empty() ? std::string("unnamed") : desc.name),
      m_bindings(desc.bindings),
      m_push_constant_size(desc.push_constant_size) {
  detail::Device& d = *m_owner;
  if (desc.descriptor_sets < 1 || desc.descriptor_sets > 64) {
    throw std::invalid_argument("pipeline '" + m_name + "': " + std::to_string(desc.descriptor_sets) +
                                " descriptor sets, expected 1 to 64");
  }
  m_bound.assign(desc.bindings.size() * desc.descriptor_sets, false);
  for (std::size_t i = 0; i < m_bindings.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (m_bindings[i].binding == m_bindings[j].binding) {
        throw std::invalid_argument("pipeline '" + m_name + "': binding " + std::to_string(m_bindings[i].binding) +
                                    " listed twice");
      }
    }
  }
  if (m_push_constant_size % 4 != 0 || m_push_constant_size > d.properties.limits.maxPushConstantsSize) {
    throw std::invalid_argument("pipeline '" + m_name + "': push-constant size " + std::to_string(m_push_constant_size) +
                                " is not a multiple of 4 in [0, " +
                                std::to_string(d.properties.limits.maxPushConstantsSize) + "]");
  }
  // The code the driver sees: the constants folded in, or the words as given.
  std::vector<std::uint32_t> folded;
  std::span<const std::uint32_t> code = desc.spirv;
  const bool fold = !desc.specialization.empty() &&
                    (desc.specialization_folding == SpecializationFolding::Folded ||
                     (desc.specialization_folding == SpecializationFolding::Auto &&
                      d.properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU));
  if (fold) {
    folded = specialize_spirv_cached(desc.spirv, desc.specialization, m_name, spirv_cache_directory(), desc.validated);
    code = folded;
  } else if (!desc.validated) {
    validate_spirv(desc.spirv, m_name);
  }

  VkShaderModule module = VK_NULL_HANDLE;
  try {
    std::vector<VkDescriptorSetLayoutBinding> layout_bindings;
    std::vector<VkDescriptorPoolSize> pool_sizes;
    for (const Binding& b : m_bindings) {
      VkDescriptorSetLayoutBinding lb{};
      lb.binding = b.binding;
      lb.descriptorType = vk_type(b.type);
      lb.descriptorCount = 1;
      lb.stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
      layout_bindings.push_back(lb);
      auto size = std::find_if(pool_sizes.begin(), pool_sizes.end(),
                               [&](const VkDescriptorPoolSize& s) { return s.type == lb.descriptorType; });
      if (size == pool_sizes.end()) {
        pool_sizes.push_back({lb.descriptorType, desc.descriptor_sets});
      } else {
        size->descriptorCount += desc.descriptor_sets;
      }
    }
    VkDescriptorSetLayoutCreateInfo set_info{};
    set_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
    set_info.bindingCount = static_cast<std::uint32_t>(layout_bindings.size());
    set_info.pBindings = layout_bindings.data();
    check(vkCreateDescriptorSetLayout(d.device, &set_info, nullptr, &m_set_layout), "vkCreateDescriptorSetLayout");

    const VkPushConstantRange push_range{VK_SHADER_STAGE_COMPUTE_BIT, 0, m_push_constant_size};
    VkPipelineLayoutCreateInfo layout_info{};
    layout_info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
    layout_info.setLayoutCount = 1;
    layout_info.pSetLayouts = &m_set_layout;
    layout_info.pushConstantRangeCount = m_push_constant_size > 0 ? 1 : 0;
    layout_info.pPushConstantRanges = &push_range;
    check(vkCreatePipelineLayout(d.device, &layout_info, nullptr, &m_layout), "vkCreatePipelineLayout");

    VkShaderModuleCreateInfo module_info{};

    module_info.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
    module_info.codeSize = code.size_bytes();
    module_info.pCode = code.data();
    check(vkCreateShaderModule(d.device, &module_info, nullptr, &module), "vkCreateShaderModule");

    // (Folded constants are in the code already: nothing to hand the driver.)
    std::vector<VkSpecializationMapEntry> entries;
    std::vector<std::uint32_t> values;
    for (const SpecializationConstant& constant : fold ? std::span<const SpecializationConstant>()
                                                       : std::span<const SpecializationConstant>(desc.specialization)) {
      entries.push_back({constant.id, static_cast<std::uint32_t>(values.size() * sizeof(std::uint32_t)),
                         sizeof(std::uint32_t)});
      values.push_back(constant.value);
    }
    VkSpecializationInfo specialization{};
    specialization.mapEntryCount = static_cast<std::uint32_t>(entries.size());
    specialization.pMapEntries = entries.data();
    specialization.dataSize = values.size() * sizeof(std::uint32_t);
    specialization.pData = values.data();

    VkComputePipelineCreateInfo pipeline_info{};

    pipeline_info.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
    pipeline_info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    pipeline_info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    pipeline_info.stage.module = module;
    pipeline_info.stage.pName = "main";
    pipeline_info.stage.pSpecializationInfo = entries.empty() ? nullptr : &specialization;
    pipeline_info.layout = m_layout;
    check(vkCreateComputePipelines(d.device, d.pipeline_cache, 1, &pipeline_info, nullptr, &m_pipeline),
          "vkCreateComputePipelines");
    vkDestroyShaderModule(d.device, module, nullptr);  // the pipeline keeps what it needs
    module = VK_NULL_HANDLE;

    if (!m_bindings.empty()) {
      VkDescriptorPoolCreateInfo pool_info{};
      pool_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
      pool_info.maxSets = desc.descriptor_sets;
      pool_info.poolSizeCount = static_cast<std::uint32_t>(pool_sizes.size());
      pool_info.pPoolSizes = pool_sizes.data();
      check(vkCreateDescriptorPool(d.device, &pool_info, nullptr, &m_pool), "vkCreateDescriptorPool");
      const std::vector<VkDescriptorSetLayout> layouts(desc.descriptor_sets, m_set_layout);
      VkDescriptorSetAllocateInfo allocate{};
      allocate.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
      allocate.descriptorPool = m_pool;
      allocate.descriptorSetCount = desc.descriptor_sets;
      allocate.pSetLayouts = layouts.data();
      m_sets.resize(desc.descriptor_sets, VK_NULL_HANDLE);
      check(vkAllocateDescriptorSets(d.device, &allocate, m_sets.data()), "vkAllocateDescriptorSets");
    } else {
      m_sets.resize(desc.descriptor_sets, VK_NULL_HANDLE);
    }
  } catch (...) {
    if (module != VK_NULL_HANDLE) vkDestroyShaderModule(d.device, module, nullptr);
    release();
    throw;
  }
}

ComputePipeline::~ComputePipeline() { release(); }

ComputePipeline::ComputePipeline(ComputePipeline&& other) noexcept
    : m_owner(std::exchange(other.m_owner, nullptr)),
      m_name(std::move(other.m_name)),
      m_bindings(std::move(other.m_bindings)),
      m_bound(std::move(other.m_bound)),
      m_push_constant_size(std::exchange(other.m_push_constant_size, 0)),
      m_set_layout(std::exchange(other.m_set_layout, VK_NULL_HANDLE)),
      m_layout(std::exchange(other.m_layout, VK_NULL_HANDLE)),
      m_pipeline(std::exchange(other.m_pipeline, VK_NULL_HANDLE)),
      m_pool(std::exchange(other.m_pool, VK_NULL_HANDLE)),
      m_sets(std::move(other.m_sets)) {}

ComputePipeline& ComputePipeline::operator=(ComputePipeline&& other) noexcept {
  if (this != &other) {
    release();
    m_owner = std::exchange(other.m_owner, nullptr);
    m_name = std::move(other.m_name);
    m_bindings = std::move(other.m_bindings);
    m_bound = std::move(other.m_bound);
    m_push_constant_size = std::exchange(other.m_push_constant_size, 0);
    m_set_layout = std::exchange(other.m_set_layout, VK_NULL_HANDLE);
    m_layout = std::exchange(other.m_layout, VK_NULL_HANDLE);
    m_pipeline = std::exchange(other.m_pipeline, VK_NULL_HANDLE);
    m_pool = std::exchange(other.m_pool, VK_NULL_HANDLE);
    m_sets = std::move(other.m_sets);
  }
  return *this;
}

void ComputePipeline::release() noexcept {
  if (m_owner == nullptr) return;
  const VkDevice device = m_owner->device;
  if (m_pool != VK_NULL_HANDLE) vkDestroyDescriptorPool(device, m_pool, nullptr);  // frees the sets
  if (m_pipeline != VK_NULL_HANDLE) vkDestroyPipeline(device, m_pipeline, nullptr);
  if (m_layout != VK_NULL_HANDLE) vkDestroyPipelineLayout(device, m_layout, nullptr);
  if (m_set_layout != VK_NULL_HANDLE) vkDestroyDescriptorSetLayout(device, m_set_layout, nullptr);
  m_pool = VK_NULL_HANDLE;
  m_sets.clear();
  m_pipeline = VK_NULL_HANDLE;
  m_layout = VK_NULL_HANDLE;
  m_set_layout = VK_NULL_HANDLE;
  m_owner = nullptr;
}

const Binding& ComputePipeline::find_binding(std::uint32_t binding, DescriptorType type, std::uint32_t set) const {
  if (m_owner == nullptr) throw std::logic_error("ComputePipeline: the pipeline was moved from");
  if (set >= m_sets.size()) {
    throw std::invalid_argument("pipeline '" + m_name + "': descriptor set " + std::to_string(set) + " of " +
                                std::to_string(m_sets.size()));
  }
  for (const Binding& b : m_bindings) {
    if (b.binding != binding) continue;
    if (b.type != type) {
      throw std::invalid_argument("pipeline '" + m_name + "': binding " + std::to_string(binding) + " is a " +
                                  type_name(b.type) + ", not a " + type_name(type));
    }
    return b;
  }
  throw std::invalid_argument("pipeline '" + m_name + "' has no binding " + std::to_string(binding));
}

void ComputePipeline::write(const Binding& b, std::uint32_t set, const VkWriteDescriptorSet& write) {
  VkWriteDescriptorSet w = write;
  w.dstSet = m_sets[set];
  w.dstBinding = b.binding;
  w.descriptorCount = 1;
  vkUpdateDescriptorSets(m_owner->device, 1, &w, 0, nullptr);
  m_bound[set * m_bindings.size() + static_cast<std::size_t>(&b - m_bindings.data())] = true;
}

void ComputePipeline::bind(std::uint32_t binding, const StorageImage& image, std::uint32_t set) {
  if (image.view() == VK_NULL_HANDLE) {
    find_binding(binding, DescriptorType::StorageImage, set);
    throw std::invalid_argument("pipeline '" + m_name + "': binding " + std::to_string(binding) +
                                ": the image was moved from");
  }
  bind(binding, image.view(), set);
}

void ComputePipeline::bind(std::uint32_t binding, VkImageView storage_view, std::uint32_t set) {
  const Binding& b = find_binding(binding, DescriptorType::StorageImage, set);
  if (storage_view == VK_NULL_HANDLE) {
    throw std::invalid_argument("pipeline '" + m_name + "': binding " + std::to_string(binding) + ": a null image view");
  }
  // GENERAL: the layout storage images are in whenever a dispatch runs.
  const VkDescriptorImageInfo info{VK_NULL_HANDLE, storage_view, VK_IMAGE_LAYOUT_GENERAL};
  VkWriteDescriptorSet w{};
  w.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
  w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
  w.pImageInfo = &info;
  write(b, set, w);
}

void ComputePipeline::bind(std::uint32_t binding, const Buffer& buffer, std::uint32_t set) {
  const bool uniform = buffer.usage() == BufferUsage::Uniform;
  const Binding& b =
      find_binding(binding, uniform ? DescriptorType::UniformBuffer : DescriptorType::StorageBuffer, set);
  if (buffer.handle() == VK_NULL_HANDLE) {
    throw std::invalid_argument("pipeline '" + m_name + "': binding " + std::to_string(binding) +
                                ": the buffer was moved from");
  }
  const VkPhysicalDeviceLimits& limits = m_owner->properties.limits;
  const VkDeviceSize max_range = uniform ? limits.maxUniformBufferRange : limits.maxStorageBufferRange;
  if (buffer.size() > max_range) {
    throw std::invalid_argument("pipeline '" + m_name + "': binding " + std::to_string(binding) + ": " +
                                std::to_string(buffer.size()) + " bytes exceed the device's limit of " +
                                std::to_string(max_range) + " for a " + type_name(b.type));
  }
  const VkDescriptorBufferInfo info{buffer.handle(), 0, VK_WHOLE_SIZE};
  VkWriteDescriptorSet w{};
  w.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
  w.descriptorType = vk_type(b.type);
  w.pBufferInfo = &info;
  write(b, set, w);
}

void ComputePipeline::check_dispatch(std::uint32_t groups_x, std::uint32_t groups_y,
                                     std::span<const std::byte> push_constants, std::uint32_t set) const {
  if (m_owner == nullptr) throw std::logic_error("ComputePipeline: the pipeline was moved from");
  if (set >= m_sets.size()) {
    throw std::invalid_argument("pipeline '" + m_name + "': descriptor set " + std::to_string(set) + " of " +
                                std::to_string(m_sets.size()));
  }
  for (std::size_t i = 0; i < m_bindings.size(); ++i) {
    if (!m_bound[set * m_bindings.size() + i]) {
      throw std::logic_error("pipeline '" + m_name + "': nothing bound to binding " +
                             std::to_string(m_bindings[i].binding) +
                             (m_sets.size() > 1 ? " of descriptor set " + std::to_string(set) : std::string()));
    }
  }
  if (push_constants.size() != m_push_constant_size) {
    throw std::invalid_argument("pipeline '" + m_name + "': " + std::to_string(push_constants.size()) +
                                " bytes of push constants, expected " + std::to_string(m_push_constant_size));
  }
  const std::uint32_t* max = m_owner->properties.limits.maxComputeWorkGroupCount;
  if (groups_x == 0 || groups_y == 0 || groups_x > max[0] || groups_y > max[1]) {
    throw std::invalid_argument("pipeline '" + m_name + "': " + std::to_string(groups_x) + "x" +
                                std::to_string(groups_y) + " workgroups outside [1, " + std::to_string(max[0]) +
                                "]x[1, " + std::to_string(max[1]) + "]");
  }
}

void ComputePipeline::record_state(VkCommandBuffer command_buffer, std::span<const std::byte> push_constants,
                                   std::uint32_t set) const {
  vkCmdBindPipeline(command_buffer, VK_PIPELINE_BIND_POINT_COMPUTE, m_pipeline);
  if (m_sets[set] != VK_NULL_HANDLE) {
    vkCmdBindDescriptorSets(command_buffer, VK_PIPELINE_BIND_POINT_COMPUTE, m_layout, 0, 1, &m_sets[set], 0, nullptr);
  }
  if (!push_constants.empty()) {
    vkCmdPushConstants(command_buffer, m_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0,
                       static_cast<std::uint32_t>(push_constants.size()), push_constants.data());
  }
}

void ComputePipeline::record_dispatch(VkCommandBuffer command_buffer, std::uint32_t groups_x, std::uint32_t groups_y,
                                      std::span<const std::byte> push_constants, std::uint32_t set) const {
  check_dispatch(groups_x, groups_y, push_constants, set);
  record_state(command_buffer, push_constants, set);
  vkCmdDispatch(command_buffer, groups_x, groups_y, 1);
}

void ComputePipeline::record_dispatch_indirect(VkCommandBuffer command_buffer, const Buffer& arguments,
                                               VkDeviceSize offset, std::span<const std::byte> push_constants,
                                               std::uint32_t set) const {
  check_dispatch(1, 1, push_constants, set);
  if (arguments.handle() == VK_NULL_HANDLE || offset % 4 != 0 || offset > arguments.size() ||
      arguments.size() - offset < sizeof(VkDispatchIndirectCommand)) {
    throw std::invalid_argument("pipeline '" + m_name + "': no dispatch command at byte " + std::to_string(offset) +
                                " of the arguments buffer");
  }
  record_state(command_buffer, push_constants, set);
  vkCmdDispatchIndirect(command_buffer, arguments.handle(), offset);
}

void record_memory_barrier(VkCommandBuffer command_buffer, VkPipelineStageFlags src_stages, VkAccessFlags src_access,
                           VkPipelineStageFlags dst_stages, VkAccessFlags dst_access) {
  VkMemoryBarrier barrier{};
  barrier.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
  barrier.srcAccessMask = src_access;
  barrier.dstAccessMask = dst_access;
  vkCmdPipelineBarrier(command_buffer, src_stages, dst_stages, 0, 1, &barrier, 0, nullptr, 0, nullptr);
}

namespace {

// One submission of `record`'s commands between the barriers run() needs,
// waited for: earlier submissions' shader writes and copies (to and from the
// same images and buffers) complete before these commands read or overwrite
// them (transfers among them too: a buffer update), and their shader writes
// are visible to the host, which reads mapped buffers as soon as this returns.
double submit_between_barriers(detail::Device& device, const std::function<void(VkCommandBuffer)>& record) {
  return device.submit_and_wait([&](VkCommandBuffer commands) {
    const VkPipelineStageFlags compute_and_transfer = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT;
    record_memory_barrier(commands, compute_and_transfer, VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT,
                          compute_and_transfer,
                          VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT);
    record(commands);
    record_memory_barrier(commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                          VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
  });
}

}  // namespace

double ComputePipeline::run(std::uint32_t groups_x, std::uint32_t groups_y, std::span<const std::byte> push_constants) {
  check_dispatch(groups_x, groups_y, push_constants, 0);  // before anything is recorded
  return submit_between_barriers(*m_owner, [&](VkCommandBuffer commands) {
    record_dispatch(commands, groups_x, groups_y, push_constants);
  });
}

double run_recorded(Context& context, const std::function<void(VkCommandBuffer)>& record) {
  return submit_between_barriers(*context.internals(), record);
}

}  // namespace sol::vk
