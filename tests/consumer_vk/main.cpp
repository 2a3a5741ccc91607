// Uses only the installed Sol::vk: a Vulkan context (the default device
// choice; lavapipe under the test), one MarchRenderer holding a preset's
// world, one frame rendered and read back, written as a PFM file (linear
// RGB floats, rows bottom to top) for the test to compare with solrender's.
//   consumer_vk SCENE WIDTH HEIGHT OUT.pfm
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include <sol/sol.hpp>
#include <sol/vk/context.hpp>
#include <sol/vk/march.hpp>

int main(int argc, char** argv) {
  if (argc != 5) {
    std::fprintf(stderr, "usage: consumer_vk SCENE WIDTH HEIGHT OUT.pfm\n");
    return 2;
  }
  try {
    const sol::Scene scene = sol::preset_scene(argv[1]);
    const int width = std::atoi(argv[2]), height = std::atoi(argv[3]);
    sol::vk::Context context;
    sol::vk::MarchRenderer renderer(context);
    renderer.set_world(scene);  // once per world
    const sol::RenderResult image = renderer.render(scene.camera, {.width = width, .height = height});
    std::FILE* out = std::fopen(argv[4], "wb");
    if (!out) throw std::runtime_error(std::string("cannot write ") + argv[4]);
    std::fprintf(out, "PF\n%d %d\n-1.0\n", width, height);  // (a negative scale: little-endian floats)
    for (int y = height - 1; y >= 0; --y) {
      for (int x = 0; x < width; ++x) std::fwrite(&image.rgba[4 * (static_cast<std::size_t>(y) * width + x)], sizeof(float), 3, out);
    }
    const bool written = std::fclose(out) == 0;
    std::printf("Sol::vk on %s: %s %dx%d -> %s\n", context.device_name().c_str(), argv[1], width, height, argv[4]);
    return written ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "consumer_vk: %s\n", e.what());
    return 1;
  }
}
