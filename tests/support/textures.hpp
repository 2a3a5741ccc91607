// Scenes and images the denoiser's and the textures' tests share (tests/,
// and render_bench's path section): a texture of distinct texels, and the
// gallery's glowing sandwich built in code.
#pragma once

#include <memory>

#include <sol/sol.hpp>

namespace sol::test {

/// A W × H texture whose texel (i, j) is (i / W, j / H, a checker of 0.25 and 0.75).
inline std::shared_ptr<const sol::Texture> gradient_texture(int w, int h) {
  auto t = std::make_shared<sol::Texture>();
  t->file = "gradient";
  t->width = w;
  t->height = h;
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      t->rgb.insert(t->rgb.end(), {static_cast<float>(static_cast<double>(i) / w), static_cast<float>(static_cast<double>(j) / h),
                                   (i + j) % 2 == 0 ? 0.25f : 0.75f});
    }
  }
  return t;
}

/// The sandwich with its upper plane (circles) glowing, lighting the lower
/// one; no lights, no ambient light, no fog: path tracing alone (as the
/// gallery's glowing-sandwich.json, in the preset's colours).
inline sol::Scene glowing_sandwich() {
  sol::Scene s = sol::preset_scene("sandwich");
  s.fog_density = 0.0;
  s.lights.clear();
  s.ambient = 0.0;
  s.objects[0].emission = {0.6, 0.5, 0.35};
  s.max_distance = 12.0;
  s.max_steps = 400;
  return s;
}

}  // namespace sol::test
