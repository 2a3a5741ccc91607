// solvkinfo: prints the Vulkan device that Sol::vk selects (name, CPU or GPU,
// Vulkan version, timestamp support).
//
//   solvkinfo                   the default choice (a GPU if any, else the CPU device)
//   solvkinfo --device cpu      SOL_VK_DEVICE=cpu does the same for every Sol program
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <string>

#include <sol/vk/vk.hpp>

namespace {

void print_usage(std::FILE* out) {
  std::fprintf(out,
               "usage: solvkinfo [--device auto|gpu|cpu] [--validation]\n"
               "Prints the Vulkan device Sol's compute library selects.\n\n"
               "  --device D     auto (default: a GPU when present, else the CPU device), gpu or cpu;\n"
               "                 without it the environment variable SOL_VK_DEVICE decides\n"
               "  --validation   enable VK_LAYER_KHRONOS_validation and report its errors\n"
               "  --help         this text\n");
}

[[noreturn]] void fail(const std::string& message) {
  std::fprintf(stderr, "solvkinfo: %s\nTry 'solvkinfo --help'.\n", message.c_str());
  std::exit(1);
}

std::string version_string(std::uint32_t version) {
  char text[32];
  std::snprintf(text, sizeof text, "%u.%u.%u", VK_API_VERSION_MAJOR(version), VK_API_VERSION_MINOR(version),
                VK_API_VERSION_PATCH(version));
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  sol::vk::ContextOptions options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      print_usage(stdout);
      return 0;
    } else if (arg == "--device") {
      if (i + 1 >= argc) fail("option --device expects auto, gpu or cpu");
      const auto preference = sol::vk::parse_device_preference(argv[++i]);
      if (!preference) fail(std::string("option --device expects auto, gpu or cpu, got '") + argv[i] + "'");
      options.preference = *preference;
    } else if (arg == "--validation") {
      options.validation = true;
    } else {
      fail("unknown option '" + arg + "'");
    }
  }
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
