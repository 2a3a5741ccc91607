// solvkinfo: prints the Vulkan device that Sol::vk selects (name, CPU or GPU,
// Vulkan version, timestamp support).
//
//   solvkinfo                   the default choice (a GPU if any, else the CPU device)
//   solvkinfo --device cpu      SOL_VK_DEVICE=cpu does the same for every Sol program
#include <cstdio>
#include <cstdint>
#include <exception>
#include <string>

#include <sol/vk/vk.hpp>

#include "command_line.hpp"

namespace {

std::string version_string(std::uint32_t version) {
  char text[32];
  std::snprintf(text, sizeof text, "%u.%u.%u", VK_API_VERSION_MAJOR(version), VK_API_VERSION_MINOR(version),
                VK_API_VERSION_PATCH(version));
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  sol::vk::ContextOptions options;
  std::string device;
  bool validation = false;
  sol::cli::CommandLine cl("solvkinfo", "[options]", "Prints the Vulkan device Sol's compute library selects.");
  cl.add_choice("--device", device, {"auto", "gpu", "cpu"},
                "auto (a GPU when present, else the CPU device), gpu or cpu; without it the environment variable "
                "SOL_VK_DEVICE decides");
  cl.add_flag("--validation", validation, "enable VK_LAYER_KHRONOS_validation and report its errors");
  cl.set_footer("Exit status 2 for bad usage, 1 when no device opens or validation reports errors.");
  cl.parse(argc, argv);
  if (!device.empty()) options.preference = *sol::vk::parse_device_preference(device);
  options.validation = validation;
  try {
    const sol::vk::Context context(options);
    std::printf("device: %s\n", context.device_name().c_str());
    std::printf("type: %s\n", context.is_cpu() ? "CPU" : "GPU");
    std::printf("vulkan: %s\n", version_string(context.api_version()).c_str());
    if (context.timestamps_supported()) {
      std::printf("timestamps: yes (%g ns per tick)\n", static_cast<double>(context.timestamp_period()));
    } else {
      std::printf("timestamps: no (timings are host times)\n");
    }
    std::printf("validation: %s\n", context.validation_enabled() ? "on" : "off");
    if (!context.validation_errors().empty()) {
      std::fprintf(stderr, "solvkinfo: %zu validation errors\n", context.validation_errors().size());
      return 1;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "solvkinfo: %s\n", e.what());
    return 1;
  }
  return 0;
}
