// Sol::vk on whatever Vulkan device ctest provides (lavapipe in CI, see
// tests/CMakeLists.txt): device choice, buffers, storage images, the fill
// kernel end to end under the validation layer, and errors that must be
// exceptions rather than crashes.
#include <algorithm>
#include <array>
#include <chrono>
#include <functional>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <sys/wait.h>
#include <vector>

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <sol/connection.hpp>
#include <sol/error.hpp>
#include <sol/vk/vk.hpp>

#include "shaders/specialised_comp_spv.hpp"

namespace {

using sol::vk::Buffer;
using sol::vk::BufferUsage;
using sol::vk::ComputePipeline;
using sol::vk::ComputePipelineDesc;
using sol::vk::Context;
using sol::vk::ContextOptions;
using sol::vk::DescriptorType;
using sol::vk::DevicePreference;
using sol::vk::StorageImage;
using sol::vk::VulkanError;

ContextOptions validated() {
  ContextOptions options;
  options.validation = true;
  return options;
}

ComputePipelineDesc fill_desc() {
  return {.name = "fill",
          .spirv = sol::vk::shaders::fill(),
          .bindings = {{0, DescriptorType::StorageImage}},
          .push_constant_size = sizeof(float)};
}

/// Sets an environment variable for one scope.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : m_name(name) {
    if (const char* old = std::getenv(name)) m_old = old;
    ::setenv(name, value, 1);
  }
  ~ScopedEnv() {
    if (m_old) {
      ::setenv(m_name, m_old->c_str(), 1);
    } else {
      ::unsetenv(m_name);
    }
  }

 private:
  const char* m_name;
  std::optional<std::string> m_old;
};

void expect_fill(const std::vector<float>& pixels, std::uint32_t width, std::uint32_t height, float value) {
  ASSERT_EQ(pixels.size(), std::size_t{width} * height * 4);
  for (std::uint32_t y = 0; y < height; ++y) {
    for (std::uint32_t x = 0; x < width; ++x) {
      const float* p = &pixels[(std::size_t{y} * width + x) * 4];
      ASSERT_EQ(p[0], static_cast<float>(x)) << "pixel " << x << "," << y;
      ASSERT_EQ(p[1], static_cast<float>(y)) << "pixel " << x << "," << y;
      ASSERT_EQ(p[2], value) << "pixel " << x << "," << y;
      ASSERT_EQ(p[3], 1.0f) << "pixel " << x << "," << y;
    }
  }
}

TEST(VkError, NamesTheCallAndTheResult) {
  const VulkanError error("vkCreateDevice", VK_ERROR_INITIALIZATION_FAILED);
  EXPECT_STREQ(error.what(), "vkCreateDevice failed: VK_ERROR_INITIALIZATION_FAILED");
  EXPECT_EQ(error.result(), VK_ERROR_INITIALIZATION_FAILED);
  EXPECT_EQ(sol::vk::result_name(VK_ERROR_DEVICE_LOST), "VK_ERROR_DEVICE_LOST");
  EXPECT_EQ(sol::vk::result_name(static_cast<VkResult>(-123456)), "VkResult(-123456)");
  EXPECT_THROW(sol::vk::check(VK_ERROR_OUT_OF_HOST_MEMORY, "vkAllocateMemory"), VulkanError);
  EXPECT_NO_THROW(sol::vk::check(VK_SUCCESS, "vkAllocateMemory"));
}

TEST(VkContext, ParsesDevicePreferences) {
  EXPECT_EQ(sol::vk::parse_device_preference("gpu"), DevicePreference::Gpu);
  EXPECT_EQ(sol::vk::parse_device_preference("CPU"), DevicePreference::Cpu);
  EXPECT_EQ(sol::vk::parse_device_preference("auto"), DevicePreference::Auto);
  EXPECT_EQ(sol::vk::parse_device_preference("tpu"), std::nullopt);
  EXPECT_EQ(sol::vk::to_string(DevicePreference::Cpu), "cpu");
}

TEST(VkContext, CpuPreferenceSelectsTheCpuDevice) {
  ContextOptions options;
  options.preference = DevicePreference::Cpu;
  const Context context(options);
  EXPECT_TRUE(context.is_cpu()) << context.device_name();
  EXPECT_EQ(context.device_type(), VK_PHYSICAL_DEVICE_TYPE_CPU);
  EXPECT_GE(context.api_version(), VK_API_VERSION_1_2);
  EXPECT_FALSE(context.device_name().empty());
  EXPECT_NE(context.device(), VK_NULL_HANDLE);
  EXPECT_NE(context.queue(), VK_NULL_HANDLE);
}

TEST(VkContext, EnvironmentOverridesAuto) {
  {
    const ScopedEnv env("SOL_VK_DEVICE", "cpu");
    EXPECT_TRUE(Context().is_cpu());
  }
  {
    const ScopedEnv env("SOL_VK_DEVICE", "banana");
    try {
      const Context context;
      FAIL() << "SOL_VK_DEVICE=banana was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("SOL_VK_DEVICE must be gpu, cpu or auto, got 'banana'"), std::string::npos)
          << e.what();
    }
  }
}

TEST(VkContext, GpuPreferenceFailsClearlyWithoutAGpu) {
  const ScopedEnv env("SOL_VK_DEVICE", "auto");
  if (!Context().is_cpu()) GTEST_SKIP() << "a GPU is present";
  ContextOptions options;
  options.preference = DevicePreference::Gpu;
  try {
    const Context context(options);
    FAIL() << "no GPU, yet a context was created on " << context.device_name();
  } catch (const VulkanError& e) {
    EXPECT_NE(std::string(e.what()).find("no usable Vulkan GPU (devices found: "), std::string::npos) << e.what();
  }
}

TEST(VkContext, MissingDeviceExtensionIsAClearError) {
  ContextOptions options;
  options.device_extensions = {"VK_SOL_no_such_extension"};
  try {
    const Context context(options);
    FAIL() << "a device claimed VK_SOL_no_such_extension";
  } catch (const VulkanError& e) {
    EXPECT_NE(std::string(e.what()).find("unusable: no VK_SOL_no_such_extension"), std::string::npos) << e.what();
  }
}

// The creation hooks (how an OpenXR runtime supplies the instance and the
// device): each is called once with the Context's create info, and the
// Context runs on what they return; a null device is a clear error.
// The fill kernel runs on `context`: a w x h image filled with `value`.
void expect_fill_runs(Context& context, std::uint32_t w, std::uint32_t h, float value) {
  StorageImage image(context, w, h);
  ComputePipeline fill(context, fill_desc());
  fill.bind(0, image);
  fill.run(1u, 1u, value);
  expect_fill(image.download(), w, h, value);
}

TEST(VkContext, CreationHooksSupplyTheInstanceAndDevice) {
  ContextOptions options = validated();
  int instances = 0, choices = 0, devices = 0;
  VkPhysicalDevice picked = VK_NULL_HANDLE;
  options.create_instance = [&](const VkInstanceCreateInfo& info, VkInstance* instance) {
    ++instances;
    EXPECT_EQ(info.pApplicationInfo->apiVersion, VK_API_VERSION_1_2);
    return vkCreateInstance(&info, nullptr, instance);
  };
  options.choose_physical_device = [&](VkInstance instance) {
    ++choices;
    std::uint32_t count = 1;
    const VkResult result = vkEnumeratePhysicalDevices(instance, &count, &picked);
    EXPECT_TRUE(result == VK_SUCCESS || result == VK_INCOMPLETE);
    return picked;
  };
  options.create_device = [&](VkPhysicalDevice physical_device, const VkDeviceCreateInfo& info, VkDevice* device) {
    ++devices;
    EXPECT_EQ(physical_device, picked);
    return vkCreateDevice(physical_device, &info, nullptr, device);
  };
  {
    Context context(options);
    EXPECT_EQ(context.physical_device(), picked);
    expect_fill_runs(context, 4, 2, 3.0f);
    EXPECT_TRUE(context.validation_errors().empty());
  }
  EXPECT_EQ(instances, 1);
  EXPECT_EQ(choices, 1);
  EXPECT_EQ(devices, 1);

  options.choose_physical_device = [](VkInstance) { return VkPhysicalDevice{VK_NULL_HANDLE}; };
  try {
    const Context context(options);
    FAIL() << "a null physical device was accepted";
  } catch (const VulkanError& e) {
    EXPECT_NE(std::string(e.what()).find("no Vulkan device was given"), std::string::npos) << e.what();
  }
}

// A Context on an application's device (here another Context's, standing
// for the application) works on it and leaves it alive: the owner's device
// still runs work after the adopting Context and its objects are gone (the
// validation layer would report a destroyed device's use).
TEST(VkContext, AdoptsAnApplicationsDeviceAndLeavesIt) {
  Context owner(validated());
  {
    Context adopted(sol::vk::ExternalDevice{.instance = owner.instance(),
                                            .physical_device = owner.physical_device(),
                                            .device = owner.device(),
                                            .queue_family = owner.queue_family_index()});
    EXPECT_EQ(adopted.device(), owner.device());
    EXPECT_EQ(adopted.queue(), owner.queue());
    EXPECT_EQ(adopted.device_name(), owner.device_name());
    expect_fill_runs(adopted, 4, 2, 5.0f);
  }
  expect_fill_runs(owner, 3, 3, 6.0f);
  EXPECT_TRUE(owner.validation_errors().empty());

  EXPECT_THROW(Context(sol::vk::ExternalDevice{}), std::invalid_argument);
  try {
    const Context bad(sol::vk::ExternalDevice{.instance = owner.instance(),
                                              .physical_device = owner.physical_device(),
                                              .device = owner.device(),
                                              .queue_family = 99});
    FAIL() << "queue family 99 was accepted";
  } catch (const VulkanError& e) {
    EXPECT_NE(std::string(e.what()).find("is not a compute queue"), std::string::npos) << e.what();
  }
}

TEST(VkContext, MovesKeepResourcesValid) {
  Context first(validated());
  StorageImage image(first, 5, 3);
  ComputePipeline fill(first, fill_desc());
  // Resources share the device, not the Context object: moving the Context
  // and then destroying it before them (it is declared last) is fine.
  Context context = std::move(first);
  fill.bind(0, image);
  fill.run(1u, 1u, 7.0f);
  StorageImage moved = std::move(image);
  EXPECT_EQ(image.handle(), VK_NULL_HANDLE);
  expect_fill(moved.download(), 5, 3, 7.0f);
  EXPECT_THROW((void)image.download(), std::logic_error);
  ComputePipeline other = std::move(fill);
  EXPECT_THROW(fill.run(1u, 1u, 7.0f), std::logic_error);
  other.bind(0, moved);
  other.run(1u, 1u, 8.0f);
  expect_fill(moved.download(), 5, 3, 8.0f);
  EXPECT_TRUE(context.validation_errors().empty());
}

TEST(VkBuffer, WritesAndReadsBack) {
  Context context(validated());
  Buffer buffer(context, 64, BufferUsage::Storage);
  EXPECT_EQ(buffer.size(), 64u);
  const std::vector<float> values{1.0f, -2.5f, 3.25f};
  buffer.write(values, 8);
  std::array<float, 3> back{};
  buffer.read(back, 8);
  EXPECT_EQ(back[0], 1.0f);
  EXPECT_EQ(back[1], -2.5f);
  EXPECT_EQ(back[2], 3.25f);
  std::array<float, 2> head{};
  buffer.read(head);  // zero-initialised
  EXPECT_EQ(head[0], 0.0f);
  EXPECT_EQ(head[1], 0.0f);
  EXPECT_THROW(buffer.write(values, 56), std::out_of_range);
  EXPECT_THROW(buffer.read(back, 100), std::out_of_range);
  EXPECT_THROW(Buffer(context, 0), std::invalid_argument);
  Buffer moved = std::move(buffer);
  EXPECT_EQ(buffer.handle(), VK_NULL_HANDLE);
  EXPECT_NE(moved.handle(), VK_NULL_HANDLE);
  EXPECT_TRUE(context.validation_errors().empty());
}

TEST(VkImage, RejectsBadExtentsAndDownloadsOnlyFloats) {
  Context context(validated());
  EXPECT_THROW(StorageImage(context, 0, 4), std::invalid_argument);
  EXPECT_THROW(StorageImage(context, 4, 1u << 30), std::invalid_argument);
  const StorageImage bytes(context, 4, 4, VK_FORMAT_R8G8B8A8_UNORM);
  EXPECT_EQ(bytes.float_channels(), 0u);
  EXPECT_THROW((void)bytes.download(), std::logic_error);
  EXPECT_TRUE(context.validation_errors().empty());
}

// The end-to-end check: 13×7 is no multiple of the 8×8 workgroup, so the
// rounded-up grid has invocations outside the image that must not write.
TEST(VkPipeline, FillWritesEveryPixelExactly) {
  Context context(validated());
  if (!context.validation_enabled()) std::fprintf(stderr, "note: validation layer not installed\n");
  constexpr std::uint32_t width = 13, height = 7;
  StorageImage image(context, width, height, VK_FORMAT_R32G32B32A32_SFLOAT);
  ComputePipeline fill(context, fill_desc());
  fill.bind(0, image);
  const double ms = fill.run(sol::vk::group_count(width, 8), sol::vk::group_count(height, 8), 0.25f);
  EXPECT_TRUE(std::isfinite(ms));
  EXPECT_GE(ms, 0.0);
  expect_fill(image.download(), width, height, 0.25f);

  // Again with another value: the pipeline and image are reusable.
  fill.run(2u, 1u, -3.5f);
  expect_fill(image.download(), width, height, -3.5f);

  const std::vector<std::string> errors = context.validation_errors();
  EXPECT_TRUE(errors.empty()) << errors.size() << " validation errors, the first: " << errors.front();
}

// FrameTimer's two timestamps around a frame's commands, against the
// submission's own timing (Context::submit_and_wait's timestamps, around
// everything the submission holds): eight dispatches of a 1024² fill between
// them take almost all of the submission's time (at least half of it, at
// most all of it and an allowance for the timestamps' rounding), in the
// right order and in milliseconds; recorded again for a second frame, the
// timer reads that frame.
TEST(VkFrameTimer, TimesTheCommandsBetweenItsTimestamps) {
  Context context(validated());
  ASSERT_TRUE(context.timestamps_supported());  // lavapipe and every GPU here write timestamps
  sol::vk::FrameTimer timer(context);
  ASSERT_TRUE(timer.supported());
  constexpr std::uint32_t side = 1024;
  StorageImage image(context, side, side, VK_FORMAT_R32G32B32A32_SFLOAT);
  ComputePipeline fill(context, fill_desc());
  fill.bind(0, image);
  for (float value : {1.0f, 2.0f}) {
    const double submission_ms = sol::vk::run_recorded(context, [&](VkCommandBuffer cb) {
      timer.begin(cb);
      for (int k = 0; k < 8; ++k) {
        if (k > 0) {
          sol::vk::record_memory_barrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                                         VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT);
        }
        fill.record_dispatch(cb, side / 8, side / 8, std::as_bytes(std::span(&value, 1)));
      }
      timer.end(cb);
    });
    const std::optional<sol::vk::FrameTimer::Reading> t = timer.read();
    ASSERT_TRUE(t.has_value());
    const double ms = timer.elapsed_ms(t->begin, t->end);
    EXPECT_GT(ms, 0.5 * submission_ms) << submission_ms;
    EXPECT_LE(ms, submission_ms + 0.01) << submission_ms;
    expect_fill(image.download(), side, side, value);
  }
  const std::vector<std::string> errors = context.validation_errors();
  EXPECT_TRUE(errors.empty()) << errors.size() << " validation errors, the first: " << errors.front();
}

// Specialisation constants folded into the SPIR-V (sol::vk::specialize_spirv,
// the default) give the program the driver gives them, and the code they
// rule out is gone before the driver sees it. tests/shaders/specialised.comp
// writes ((x + OFFSET) * SCALE, y, SQUARE ? v² + 2 OFFSET : 0, 1): small
// integers and halves, exact in float, so both ways are held to the host's
// values exactly. A constant the module does not declare (id 7) is ignored
// either way, as Vulkan ignores it.
// The display pass (sol::vk::DisplayPass) of a float image: fill's (x, y,
// 0.3, 1) over 13 x 7 pixels (values 0 to 12: most above white) shown
// through each curve, against the curves from their definitions (clamp:
// min(x 2^e, 1); aces: Narkowicz's rational fit of x 2^e), to float
// rounding; pixels outside the size asked for are left as they were.
TEST(VkPipeline, TheDisplayPassShowsTheImageThroughTheCurve) {
  Context context(validated());
  constexpr std::uint32_t width = 13, height = 7;
  StorageImage linear(context, width, height);
  ComputePipeline fill(context, fill_desc());
  fill.bind(0, linear);
  fill.run(sol::vk::group_count(width, 8), sol::vk::group_count(height, 8), 0.3f);
  sol::vk::DisplayPass pass(context, 2);
  for (const sol::Display display : {sol::Display{0.0, sol::Tone::Clamp}, sol::Display{-3.0, sol::Tone::Clamp},
                                     sol::Display{0.0, sol::Tone::Aces}, sol::Display{-2.5, sol::Tone::Aces}}) {
    StorageImage shown(context, width, height);
    fill.bind(0, shown, 0);
    fill.run(sol::vk::group_count(width, 8), sol::vk::group_count(height, 8), -1.0f);  // outside: (x, y, -1, 1)
    context.submit_and_wait([&](VkCommandBuffer cb) { pass.record(cb, linear, shown, 12, 6, display, 1); });
    const std::vector<float> in = linear.download(), out = shown.download();
    double worst = 0.0;
    for (std::uint32_t y = 0; y < height; ++y) {
      for (std::uint32_t x = 0; x < width; ++x) {
        const std::size_t k = (std::size_t{y} * width + x) * 4;
        if (x >= 12 || y >= 6) {
          EXPECT_EQ(out[k + 2], -1.0f) << x << "," << y;
          continue;
        }
        for (std::size_t c = 0; c < 3; ++c) {
          const double v = in[k + c] * std::exp2(display.exposure);
          const double want = display.tone == sol::Tone::Aces
                                  ? std::min(v * (2.51 * v + 0.03) / (v * (2.43 * v + 0.59) + 0.14), 1.0)
                                  : std::min(v, 1.0);
          worst = std::max(worst, std::abs(out[k + c] - want));
        }
        EXPECT_EQ(out[k + 3], 1.0f);
      }
    }
    EXPECT_LT(worst, 1e-6) << display.exposure << " " << sol::tone_name(display.tone);
    fill.bind(0, linear, 0);
  }
  EXPECT_THROW(context.submit_and_wait([&](VkCommandBuffer cb) { pass.record(cb, linear, linear, 12, 6, {}, 2); }),
               sol::InvalidArgument);
  EXPECT_THROW(context.submit_and_wait([&](VkCommandBuffer cb) { pass.record(cb, linear, linear, 14, 6, {}, 0); }),
               sol::InvalidArgument);
  const std::vector<std::string> errors = context.validation_errors();
  EXPECT_TRUE(errors.empty()) << errors.size() << " validation errors, the first: " << errors.front();
}

TEST(VkPipeline, FoldedSpecialisationIsTheDriversAndDropsDeadCode) {
  Context context(validated());
  const std::span<const std::uint32_t> words(specialised_comp_spv);
  constexpr std::uint32_t width = 11, height = 5;
  // Opcodes: OpSpecConstantTrue..OpSpecConstantOp are 48..52, OpFunction 54.
  const auto count_opcodes = [](std::span<const std::uint32_t> code, std::uint32_t first, std::uint32_t last) {
    int n = 0;
    for (std::size_t at = 5; at < code.size() && (code[at] >> 16) > 0; at += code[at] >> 16) {
      n += (code[at] & 0xffffu) >= first && (code[at] & 0xffffu) <= last;
    }
    return n;
  };
  EXPECT_EQ(count_opcodes(words, 54, 54), 2) << "main and squared";
  EXPECT_GE(count_opcodes(words, 48, 52), 4) << "SQUARE, OFFSET, SCALE and 2 * OFFSET";
  for (const bool square : {false, true}) {
    const int offset = 3;
    const float scale = 0.5f;
    const std::vector<sol::vk::SpecializationConstant> constants = {
        {0, square ? 1u : 0u}, {1, static_cast<std::uint32_t>(offset)}, {2, std::bit_cast<std::uint32_t>(scale)}, {7, 42u}};
    const std::vector<std::uint32_t> folded = sol::vk::specialize_spirv(words, constants, "specialised");
    EXPECT_EQ(count_opcodes(folded, 48, 52), 0) << "no specialisation constant left";
    EXPECT_EQ(count_opcodes(folded, 54, 54), square ? 2 : 1) << "squared() only where it is called";
    for (const bool fold : {true, false}) {
      StorageImage image(context, width, height, VK_FORMAT_R32G32B32A32_SFLOAT);
      ComputePipeline pipeline(context, {.name = "specialised",
                                         .spirv = words,
                                         .bindings = {{0, DescriptorType::StorageImage}},
                                         .specialization = constants,
                                         .specialization_folding = fold ? sol::vk::SpecializationFolding::Folded
                                                                        : sol::vk::SpecializationFolding::Driver});
      pipeline.bind(0, image);
      pipeline.run(sol::vk::group_count(width, 8), sol::vk::group_count(height, 8));
      const std::vector<float> pixels = image.download();
      int wrong = 0;
      for (std::uint32_t y = 0; y < height; ++y) {
        for (std::uint32_t x = 0; x < width; ++x) {
          const float v = static_cast<float>(static_cast<int>(x) + offset) * scale;
          const float expected[4] = {v, static_cast<float>(y), square ? v * v + 2.0f * offset : 0.0f, 1.0f};
          for (int c = 0; c < 4; ++c) wrong += pixels[4 * (y * width + x) + c] != expected[c];
        }
      }
      EXPECT_EQ(wrong, 0) << (fold ? "folded" : "by the driver") << (square ? ", SQUARE" : "");
    }
  }
  // Not SPIR-V: the same error as the pipeline's.
  const std::vector<std::uint32_t> garbage(16, 0x12345678u);
  EXPECT_THROW(sol::vk::specialize_spirv(garbage, {}, "garbage"), VulkanError);
  // Words known valid (`validated`, the project's kernels) fold to the same
  // module unchecked; the folded module is still checked: without its entry
  // point (OpEntryPoint, opcode 15, taken out) the module is rejected
  // whether or not its words were said to be valid.
  const std::vector<sol::vk::SpecializationConstant> square = {{0, 1u}};
  EXPECT_EQ(sol::vk::specialize_spirv(words, square, "validated", true),
            sol::vk::specialize_spirv(words, square, "validated"));
  std::vector<std::uint32_t> no_entry(words.begin(), words.begin() + 5);
  for (std::size_t at = 5; at < words.size(); at += words[at] >> 16) {
    if ((words[at] & 0xffffu) != 15u) no_entry.insert(no_entry.end(), words.begin() + at, words.begin() + at + (words[at] >> 16));
  }
  ASSERT_LT(no_entry.size(), words.size());
  EXPECT_THROW(sol::vk::specialize_spirv(no_entry, square, "no entry point"), VulkanError);
  EXPECT_THROW(sol::vk::specialize_spirv(no_entry, square, "no entry point, said valid", true), VulkanError);
  const std::vector<std::string> errors = context.validation_errors();
  EXPECT_TRUE(errors.empty()) << errors.size() << " validation errors, the first: " << errors.front();
}

// What a cache read must survive in place of its file: a FIFO (opening it
// to read would wait for a writer), a link to /dev/zero (never ends), a
// directory, a sparse file of a terabyte. Each is passed over at once.
// `check` runs with the hostile file in place, under a watchdog.
void expect_hostile_cache_files_passed_over(const std::filesystem::path& file, const std::function<void()>& check) {
  namespace fs = std::filesystem;
  const auto within_seconds = [&](const char* what) {
    const auto begin = std::chrono::steady_clock::now();
    check();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    EXPECT_LT(seconds, 30.0) << what;
  };
  fs::remove_all(file);
  ASSERT_EQ(::mkfifo(file.c_str(), 0600), 0);
  within_seconds("a FIFO");
  fs::remove(file);
  fs::create_symlink("/dev/zero", file);
  within_seconds("a link to /dev/zero");
  fs::remove(file);
  fs::create_directory(file);
  within_seconds("a directory");
  fs::remove_all(file);
  {
    std::ofstream sparse(file, std::ios::binary);
    sparse.seekp((std::streamoff{1} << 40) - 1);  // a terabyte, almost all holes
    sparse.put('\0');
  }
  within_seconds("a sparse terabyte");  // (and `check` put a cache file in its place)
}

// Folded modules kept on disk (sol::vk::specialize_spirv_cached, what
// pipelines use with spirv_cache_directory()): the first fold writes one
// cache file, holding the module specialize_spirv makes under its key; the
// same words and constants in another order read that file back (shown by
// planting another valid module there under the same key: it is what
// comes back); other constants make another file. A file is read back
// only when it holds what was written for its key: another variant's file
// copied under this name (a valid module that would render garbage), a
// body zeroed after its header, a truncated file or one that is not a
// cache file at all is passed over, the module folded again and the file
// mended; so is a FIFO, a link to /dev/zero, a directory or a sparse
// terabyte, without waiting or reading it; without a directory nothing is
// written.
TEST(VkPipeline, FoldedModulesAreKeptOnDisk) {
  const std::span<const std::uint32_t> words(specialised_comp_spv);
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("sol-spirv-cache-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  const std::vector<sol::vk::SpecializationConstant> square = {{0, 1u}, {1, 3u}, {2, std::bit_cast<std::uint32_t>(0.5f)}};
  const std::vector<sol::vk::SpecializationConstant> reordered = {square[2], square[0], square[1]};
  const std::vector<sol::vk::SpecializationConstant> plain = {{0, 0u}, {1, 3u}, {2, std::bit_cast<std::uint32_t>(0.5f)}};
  const std::vector<std::uint32_t> expected = sol::vk::specialize_spirv(words, square, "specialised");
  const std::vector<std::uint32_t> other = sol::vk::specialize_spirv(words, plain, "specialised");
  ASSERT_NE(expected, other);
  auto files = [&] {
    std::vector<std::filesystem::path> found;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) found.push_back(entry.path());
    return found;
  };
  EXPECT_EQ(sol::vk::specialize_spirv_cached(words, square, "specialised", dir), expected);
  ASSERT_EQ(files().size(), 1u);
  const std::filesystem::path kept = files().front();
  const std::uintmax_t whole = std::filesystem::file_size(kept);
  const std::uint64_t key = sol::vk::spirv_cache_key(words, square);
  ASSERT_EQ(sol::vk::read_cache_file(kept)->key, key);
  EXPECT_EQ(sol::vk::read_cache_file(kept)->words, expected);
  sol::vk::write_cache_file(kept, key, other);  // planted under this key
  EXPECT_EQ(sol::vk::specialize_spirv_cached(words, reordered, "specialised", dir), other);  // read back, not folded
  EXPECT_EQ(sol::vk::specialize_spirv_cached(words, plain, "specialised", dir), other);
  ASSERT_EQ(files().size(), 2u);
  const std::filesystem::path plain_file = files()[0] == kept ? files()[1] : files()[0];
  auto raw = [](const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    return std::vector<char>(std::istreambuf_iterator<char>(in), {});
  };
  auto rewrite = [](const std::filesystem::path& file, const std::vector<char>& bytes) {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  };
  auto mended = [&](const char* what) {
    EXPECT_EQ(sol::vk::specialize_spirv_cached(words, square, "specialised", dir), expected) << what;
    EXPECT_EQ(std::filesystem::file_size(kept), whole) << what;
    EXPECT_EQ(sol::vk::read_cache_file(kept)->words, expected) << what;
  };
  // Another variant's file (a valid module, its own key) copied under this name.
  rewrite(kept, raw(plain_file));
  mended("another variant's file");
  // The header kept, the body zeroed.
  std::vector<char> zeroed = raw(kept);
  std::fill(zeroed.begin() + 7 * 4, zeroed.end(), '\0');
  rewrite(kept, zeroed);
  mended("a zeroed body");
  std::vector<char> truncated = raw(kept);
  truncated.resize(truncated.size() - 4);
  rewrite(kept, truncated);
  mended("a truncated file");
  rewrite(kept, {'n', 'o', 't', ' ', 'a', ' ', 'm', 'o', 'd', 'u', 'l', 'e'});
  mended("not a cache file");
  expect_hostile_cache_files_passed_over(kept, [&] {
    EXPECT_EQ(sol::vk::specialize_spirv_cached(words, square, "specialised", dir), expected);
  });
  EXPECT_EQ(sol::vk::specialize_spirv_cached(words, square, "specialised", std::nullopt), expected);
  EXPECT_EQ(files().size(), 2u);  // no partial files left
  std::filesystem::remove_all(dir);
}

// The connection solver's seeds the kernel reads are compiled in at build
// time (sol::vk::connection_seeds): they are the tables libsol's solver
// builds now, to the bit (the longer connections' too with
// SOL_FULL_SWEEPS=1: about 5 s of two cores).
TEST(VkPipeline, TheCompiledInSeedsAreTheSolversTables) {
  const std::vector<float> built = sol::ConnectionTable::build(false).seeds;
  const std::span<const float> kept = sol::vk::connection_seeds(false);
  ASSERT_EQ(kept.size(), built.size());
  EXPECT_TRUE(std::equal(kept.begin(), kept.end(), built.begin(), [](float a, float b) {
    return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b);
  }));
  if (std::getenv("SOL_FULL_SWEEPS") != nullptr) {
    const std::vector<float> longer = sol::ConnectionTable::build(true).seeds;
    const std::span<const float> kept_longer = sol::vk::connection_seeds(true);
    ASSERT_EQ(kept_longer.size(), longer.size());
    EXPECT_TRUE(std::equal(kept_longer.begin(), kept_longer.end(), longer.begin(), [](float a, float b) {
      return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b);
    }));
  }
}

// An indirect dispatch takes its workgroup counts from a buffer: (1, 1, 1)
// fills the first 8 x 8 group of a 16 x 16 image alone, (2, 2, 1) all of it;
// a command past the buffer's end throws. The device's own buffers
// (DeviceStorage) are not mapped: reading or writing them from the host throws.
TEST(VkPipeline, IndirectDispatchTakesItsGroupsFromTheBuffer) {
  Context context(validated());
  StorageImage image(context, 16, 16, VK_FORMAT_R32G32B32A32_SFLOAT);
  ComputePipeline fill(context, fill_desc());
  fill.bind(0, image);
  fill.run(2u, 2u, 0.0f);
  Buffer arguments(context, 2 * sizeof(VkDispatchIndirectCommand));
  const std::uint32_t commands[6] = {1, 1, 1, 2, 2, 1};
  arguments.write(commands);
  const float value = 5.0f;
  const auto push = std::as_bytes(std::span(&value, 1));
  context.submit_and_wait([&](VkCommandBuffer cb) { fill.record_dispatch_indirect(cb, arguments, 0, push); });
  std::vector<float> pixels = image.download();
  for (int y = 0; y < 16; ++y) {
    for (int x = 0; x < 16; ++x) {
      EXPECT_EQ(pixels[(static_cast<std::size_t>(y) * 16 + x) * 4 + 2], x < 8 && y < 8 ? 5.0f : 0.0f) << x << ", " << y;
    }
  }
  context.submit_and_wait([&](VkCommandBuffer cb) {
    fill.record_dispatch_indirect(cb, arguments, sizeof(VkDispatchIndirectCommand), push);
  });
  expect_fill(image.download(), 16, 16, 5.0f);
  context.submit_and_wait([&](VkCommandBuffer cb) {
    EXPECT_THROW(fill.record_dispatch_indirect(cb, arguments, 2 * sizeof(VkDispatchIndirectCommand) - 4, push),
                 std::invalid_argument);
    EXPECT_THROW(fill.record_dispatch_indirect(cb, arguments, 2, push), std::invalid_argument);
  });

  Buffer device_only(context, 64, BufferUsage::DeviceStorage);
  std::vector<float> values(4, 1.0f);
  EXPECT_THROW(device_only.write(values), std::logic_error);
  EXPECT_THROW(device_only.read(values), std::logic_error);
  EXPECT_TRUE(device_only.bytes().empty());
  const std::vector<std::string> errors = context.validation_errors();
  EXPECT_TRUE(errors.empty()) << errors.size() << " validation errors, the first: " << errors.front();
}

// The pipeline cache kept between runs (ContextOptions::pipeline_cache_dir):
// written when the Context ends with this device's header; read back by the
// next Context (pipeline_cache_loaded_bytes() is how a second run is seen to
// use it: on lavapipe the driver's data is the 32-byte header alone, so that
// is all it holds there); a garbage, truncated or foreign file is ignored
// with a warning and rewritten; an unwritable place is a warning, not an error.
TEST(VkContext, PipelineCacheIsKeptAndBadFilesAreIgnored) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(testing::TempDir()) / "sol-pipeline-cache";
  fs::remove_all(dir);
  ContextOptions options;
  options.pipeline_cache_dir = dir.string();
  std::string path;
  std::array<std::uint8_t, 16 + VK_UUID_SIZE> header{};
  {
    Context context(options);
    path = context.pipeline_cache_path();
    EXPECT_EQ(fs::path(path).parent_path(), dir);
    EXPECT_EQ(context.pipeline_cache_loaded_bytes(), 0u);  // nothing there yet
    ComputePipeline fill(context, fill_desc());            // created through the cache
    const VkPhysicalDeviceProperties& p = context.properties();
    const std::uint32_t words[4] = {16 + VK_UUID_SIZE, VK_PIPELINE_CACHE_HEADER_VERSION_ONE, p.vendorID, p.deviceID};
    std::memcpy(header.data(), words, sizeof words);
    std::memcpy(header.data() + 16, p.pipelineCacheUUID, VK_UUID_SIZE);
  }
  auto read = [](const std::string& file) {
    std::ifstream in(file, std::ios::binary);
    return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  };
  const std::vector<std::uint8_t> written = read(path);
  ASSERT_GE(written.size(), header.size());
  EXPECT_TRUE(std::equal(header.begin(), header.end(), written.begin())) << "the file's header is this device's";
  {
    Context again(options);
    EXPECT_EQ(again.pipeline_cache_loaded_bytes(), written.size()) << "the second run reads what the first wrote";
  }
  auto loads_with_warning = [&](const std::vector<std::uint8_t>& contents, const std::string& why) {
    std::ofstream(path, std::ios::binary | std::ios::trunc)
        .write(reinterpret_cast<const char*>(contents.data()), static_cast<std::streamsize>(contents.size()));
    testing::internal::CaptureStderr();
    std::size_t loaded = 1;
    {
      Context context(options);
      loaded = context.pipeline_cache_loaded_bytes();
    }
    const std::string err = testing::internal::GetCapturedStderr();
    EXPECT_EQ(loaded, 0u) << why;
    EXPECT_NE(err.find("ignoring the pipeline cache"), std::string::npos) << why << ": " << err;
    EXPECT_NE(err.find(why), std::string::npos) << err;
    const std::vector<std::uint8_t> rewritten = read(path);
    EXPECT_TRUE(rewritten.size() >= header.size() && std::equal(header.begin(), header.end(), rewritten.begin()))
        << why << ": rewritten for this device";
  };
  loads_with_warning(std::vector<std::uint8_t>(100, 0x5a), "truncated or not a pipeline cache");
  loads_with_warning(std::vector<std::uint8_t>(written.begin(), written.begin() + 20), "truncated or not a pipeline cache");
  std::vector<std::uint8_t> foreign = written;
  foreign[8] ^= 0xff;  // another vendor
  loads_with_warning(foreign, "written by another device or driver");
  // Not a file at all: a directory (which also cannot be replaced at the
  // end), a FIFO (reading it would block) and a link to /dev/zero (which
  // never ends) are ignored with a warning that names the cache.
  const auto ignored = [&](const std::string& why) {
    testing::internal::CaptureStderr();
    std::size_t loaded = 1;
    EXPECT_NO_THROW({
      Context context(options);
      loaded = context.pipeline_cache_loaded_bytes();
    }) << why;
    const std::string err = testing::internal::GetCapturedStderr();
    EXPECT_EQ(loaded, 0u) << why;
    EXPECT_NE(err.find("ignoring the pipeline cache " + path + ": " + why), std::string::npos) << err;
    return err;
  };
  fs::remove(path);
  fs::create_directory(path);
  EXPECT_NE(ignored("it is a directory").find("cannot write the pipeline cache " + path), std::string::npos);
  fs::remove_all(path);
  ASSERT_EQ(::mkfifo(path.c_str(), 0600), 0);
  ignored("it is not a regular file");
  fs::remove(path);
  fs::create_symlink("/dev/zero", path);
  ignored("it is not a regular file");
  fs::remove(path);
  // A cache directory under a regular file cannot be made: a warning at the end, no exception.
  std::ofstream(dir / "file") << "x";
  ContextOptions blocked;
  blocked.pipeline_cache_dir = (dir / "file" / "sub").string();
  testing::internal::CaptureStderr();
  EXPECT_NO_THROW({ Context context(blocked); });
  EXPECT_NE(testing::internal::GetCapturedStderr().find("cannot write the pipeline cache"), std::string::npos);
}

// The empty validation_errors() elsewhere mean something only if the layer
// and its synchronisation validation are really listening.
TEST(VkValidation, ReportsAMissingBarrier) {
  Context context(validated());
  if (!context.validation_enabled()) GTEST_SKIP() << "VK_LAYER_KHRONOS_validation is not installed";
  Buffer source(context, 256), target(context, 256);
  // Two copies into the same buffer with no barrier between them.
  context.submit_and_wait([&](VkCommandBuffer commands) {
    const VkBufferCopy region{0, 0, 256};
    vkCmdCopyBuffer(commands, source.handle(), target.handle(), 1, &region);
    vkCmdCopyBuffer(commands, source.handle(), target.handle(), 1, &region);
  });
  const std::vector<std::string> errors = context.validation_errors();
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_NE(errors.front().find("SYNC-HAZARD-WRITE-AFTER-WRITE"), std::string::npos) << errors.front();
}

TEST(VkPipeline, InvalidSpirvThrowsInsteadOfCrashing) {
  Context context(validated());
  const std::vector<std::uint32_t> garbage{0xdeadbeefu, 0x00010500u, 0u, 8u, 0u, 0x12345678u};
  const std::vector<std::uint32_t> header_only{0x07230203u, 0x00010500u, 0u, 8u, 0u};
  const std::span<const std::uint32_t> fill = sol::vk::shaders::fill();
  const std::vector<std::uint32_t> truncated(fill.begin(), fill.begin() + static_cast<std::ptrdiff_t>(fill.size() / 2));
  for (const auto* words : {&garbage, &header_only, &truncated}) {
    ComputePipelineDesc desc = fill_desc();
    desc.spirv = *words;
    try {
      ComputePipeline pipeline(context, desc);
      FAIL() << "invalid SPIR-V of " << words->size() << " words was accepted";
    } catch (const VulkanError& e) {
      EXPECT_NE(std::string(e.what()).find("pipeline 'fill': invalid SPIR-V"), std::string::npos) << e.what();
    }
  }
  ComputePipelineDesc empty = fill_desc();
  empty.spirv = {};
  EXPECT_THROW(ComputePipeline(context, empty), VulkanError);
  // Rejected before the driver saw it: the validation layer has nothing to say.
  EXPECT_TRUE(context.validation_errors().empty());
}

// A caller's image view (a presenter's swapchain image, say) binds as a
// StorageImage does: the dispatch writes that image.
TEST(VkPipeline, BindsACallersImageView) {
  Context context(validated());
  StorageImage image(context, 5, 3);
  ComputePipeline fill(context, fill_desc());
  fill.bind(0, image.view());
  fill.run(1u, 1u, 2.5f);
  const std::vector<float> pixels = image.download();
  for (std::uint32_t y = 0; y < 3; ++y) {
    for (std::uint32_t x = 0; x < 5; ++x) {
      const std::size_t k = (std::size_t{y} * 5 + x) * 4;
      EXPECT_EQ(pixels[k + 0], static_cast<float>(x));
      EXPECT_EQ(pixels[k + 1], static_cast<float>(y));
      EXPECT_EQ(pixels[k + 2], 2.5f);
    }
  }
  EXPECT_TRUE(context.validation_errors().empty());
}

TEST(VkPipeline, MisuseThrows) {
  Context context(validated());
  StorageImage image(context, 8, 8);
  Buffer storage(context, 16, BufferUsage::Storage);
  ComputePipeline fill(context, fill_desc());
  EXPECT_THROW(fill.run(1u, 1u, 1.0f), std::logic_error);  // nothing bound yet
  EXPECT_THROW(fill.bind(0, storage), std::invalid_argument);
  EXPECT_THROW(fill.bind(1, image), std::invalid_argument);
  EXPECT_THROW(fill.bind(0, VkImageView{VK_NULL_HANDLE}), std::invalid_argument);
  EXPECT_THROW(fill.bind(1, image.view()), std::invalid_argument);  // no binding 1
  fill.bind(0, image);
  EXPECT_THROW(fill.run(1u, 1u), std::invalid_argument);           // no push constants
  EXPECT_THROW(fill.run(1u, 1u, 1.0), std::invalid_argument);      // a double: 8 bytes
  EXPECT_THROW(fill.run(0u, 1u, 1.0f), std::invalid_argument);     // no groups
  ComputePipelineDesc twice = fill_desc();
  twice.bindings.push_back({0, DescriptorType::StorageBuffer});
  EXPECT_THROW(ComputePipeline(context, twice), std::invalid_argument);
  ComputePipelineDesc odd = fill_desc();
  odd.push_constant_size = 6;
  EXPECT_THROW(ComputePipeline(context, odd), std::invalid_argument);
  EXPECT_TRUE(context.validation_errors().empty());
}

TEST(VkPipeline, GroupCountRoundsUp) {
  EXPECT_EQ(sol::vk::group_count(13, 8), 2u);
  EXPECT_EQ(sol::vk::group_count(16, 8), 2u);
  EXPECT_EQ(sol::vk::group_count(1, 8), 1u);
  EXPECT_EQ(sol::vk::group_count(0, 8), 0u);
}

#ifdef SOLVKINFO_PATH
/// Runs solvkinfo with `args`; returns its exit status and, in `output`, its
/// stdout and stderr together.
int run_solvkinfo(const std::string& args, std::string& output) {
  const std::string command = std::string("'") + SOLVKINFO_PATH + "' " + args + " 2>&1";
  std::FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return -1;
  std::array<char, 256> chunk{};
  while (std::fgets(chunk.data(), static_cast<int>(chunk.size()), pipe) != nullptr) output += chunk.data();
  const int status = ::pclose(pipe);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(SolVkInfo, PrintsTheDeviceAndFailsCleanly) {
  std::string out;
  EXPECT_EQ(run_solvkinfo("--device cpu", out), 0) << out;
  EXPECT_NE(out.find("type: CPU"), std::string::npos) << out;
  EXPECT_NE(out.find("vulkan: 1."), std::string::npos) << out;
  out.clear();
  EXPECT_EQ(run_solvkinfo("--help", out), 0) << out;
  EXPECT_NE(out.find("usage: solvkinfo"), std::string::npos) << out;
  out.clear();
  // Bad usage: exit status 2, the programs' wording.
  EXPECT_EQ(run_solvkinfo("--device tpu", out), 2) << out;
  EXPECT_NE(out.find("solvkinfo: option --device expects auto, gpu or cpu, got 'tpu'"), std::string::npos) << out;
  out.clear();
  EXPECT_EQ(run_solvkinfo("--frobnicate", out), 2) << out;
  EXPECT_NE(out.find("unknown option '--frobnicate'"), std::string::npos) << out;
}
#endif

}  // namespace
