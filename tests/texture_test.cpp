// Image textures (sol/texture.h, sol/texture.hpp) on the CPU renderer: the
// mapping against a bilinear lookup written out here from its definition
// (texel centres at ((i + 1/2) / W, 1 − (j + 1/2) / H) of one copy spread
// over `cells` pattern cells, its centre at the pattern origin), the
// albedo AOV of a rendered textured plane and ball against that lookup at
// each hit's pattern coordinates, and the scene file's keys (read through
// a reader installed here, so without image files), their errors by field.
// The kernel's textures are compared with these in kernel_texture_test.cpp.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <sol/sol.hpp>

#include "support/textures.hpp"

namespace {

using sol::test::gradient_texture;

// The texture's colour at pattern coordinates (u, v), from the definition:
// the point of the unit square (s, t) = frac((u, v) / cells + 1/2), in texel
// units x = s W − 1/2, y = (1 − t) H − 1/2 (rows from the top), bilinear
// between the four texel centres around it, indices taken modulo the size.
glm::dvec3 expected_color(const sol::Texture& t, glm::dvec2 cells, double u, double v) {
  const double s = u / cells.x + 0.5, tt = v / cells.y + 0.5;
  const double x = (s - std::floor(s)) * t.width - 0.5, y = (1.0 - (tt - std::floor(tt))) * t.height - 0.5;
  const double fx = x - std::floor(x), fy = y - std::floor(y);
  auto texel = [&](double i, double j) {
    const int a = ((static_cast<int>(std::floor(i)) % t.width) + t.width) % t.width;
    const int b = ((static_cast<int>(std::floor(j)) % t.height) + t.height) % t.height;
    const std::size_t k = 3 * (static_cast<std::size_t>(b) * t.width + a);
    return glm::dvec3(t.rgb[k], t.rgb[k + 1], t.rgb[k + 2]);
  };
  return (1 - fx) * (1 - fy) * texel(x, y) + fx * (1 - fy) * texel(x + 1, y) + (1 - fx) * fy * texel(x, y + 1) +
         fx * fy * texel(x + 1, y + 1);
}

TEST(Texture, TheLookupIsTheBilinearImageOfItsDefinition) {
  const auto t = gradient_texture(5, 3);
  for (const glm::dvec2 cells : {glm::dvec2(1.0, 1.0), glm::dvec2(2.0, 0.5), glm::dvec2(8.0, 4.0)}) {
    for (double u = -3.7; u < 3.7; u += 0.173) {
      for (double v = -2.9; v < 2.9; v += 0.191) {
        const glm::dvec3 got = sol::texture_color(*t, cells, {u, v}), want = expected_color(*t, cells, u, v);
        EXPECT_NEAR(got.r, want.r, 1e-12) << u << ", " << v;
        EXPECT_NEAR(got.g, want.g, 1e-12) << u << ", " << v;
        EXPECT_NEAR(got.b, want.b, 1e-12) << u << ", " << v;
      }
    }
  }
  // A texel's centre is its own colour: texel (1, 0) of 2 × 2 over one cell
  // is at s = 3/4, t = 3/4, so (u, v) = (1/4, 1/4); and a copy later, the same.
  const auto small = gradient_texture(2, 2);
  for (const double shift : {0.0, 1.0, -3.0}) {
    const glm::dvec3 c = sol::texture_color(*small, {1.0, 1.0}, {0.25 + shift, 0.25 - shift});
    EXPECT_NEAR(c.r, 0.5, 1e-12);
    EXPECT_NEAR(c.g, 0.0, 1e-12);
    EXPECT_NEAR(c.b, 0.75, 1e-12);
  }
}

// Renders `scene` on the CPU with its AOVs, checks each hit pixel's albedo
// against the object's colour times expected_color at its pattern
// coordinates (`uv_of` from the hit point), and returns the pixels checked.
template <class Uv>
int expect_textured_albedo(const sol::Scene& scene, int textured, Uv uv_of) {
  sol::RenderOptions options;
  options.width = 40;
  options.height = 30;
  options.guides = true;
  const sol::RenderResult r = sol::render_cpu(scene, options);
  const sol::SceneObject& o = scene.objects[static_cast<std::size_t>(textured)];
  int checked = 0;
  for (std::size_t k = 0; k < r.object.size(); ++k) {
    if (static_cast<int>(r.object[k]) != textured + 1) continue;
    const glm::dvec2 uv = uv_of(glm::dvec3(r.px[k], r.py[k], r.pz[k]));
    const glm::dvec3 want = o.color * expected_color(*o.texture, o.texture_cells, uv.x, uv.y);
    // (The AOV's hit point is float: a texel's colour changes by at most
    // 1 across it, a few texels a cell: 1e-5.)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(r.albedo[3 * k + c], want[c], 1e-5) << "pixel " << k;
    ++checked;
  }
  return checked;
}

TEST(Texture, APlanesTextureLandsWhereItsPatternCoordinatesSay) {
  // The plane z = -1 seen from above: its pattern coordinates are the hit's x, y.
  sol::Scene scene = sol::preset_scene("plane");
  scene.camera = {{0.3, -0.2, 0.5}, glm::normalize(glm::dvec3(0.2, 0.1, -1.0)), {0.0, 1.0, 0.0}, 80.0};
  scene.objects = {{sol::PlaneZ{-1.0}, {0.9, 0.8, 1.0}}};
  scene.objects[0].texture = gradient_texture(6, 4);
  scene.objects[0].texture_cells = {2.0, 0.5};
  const int checked = expect_textured_albedo(scene, 0, [](const glm::dvec3& p) { return glm::dvec2(p.x, p.y); });
  EXPECT_GT(checked, 300);  // (of 1200 pixels: geodesics bend away from the plane)
}

TEST(Texture, ABallsTextureWrapsItOnceAtEightByFourCells) {
  // A ball's pattern coordinates: (4/π) times its longitude and latitude
  // about its centre (sol/patterns.h), here at the origin: 8 × 4 cells.
  sol::Scene scene = sol::preset_scene("plane");
  scene.camera = {{2.0, 0.3, 0.4}, glm::normalize(glm::dvec3(-1.0, -0.1, -0.2)), {0.0, 0.0, 1.0}, 60.0};
  scene.objects = {{sol::Ball{{0.0, 0.0, 0.0}, 0.6}, {1.0, 1.0, 1.0}}};
  scene.objects[0].texture = gradient_texture(16, 8);
  scene.objects[0].texture_cells = {8.0, 4.0};
  const double cells_per_radian = 4.0 / std::acos(-1.0);
  const int checked = expect_textured_albedo(scene, 0, [&](const glm::dvec3& p) {
    return cells_per_radian * glm::dvec2(std::atan2(p.y, p.x), std::atan2(p.z, std::hypot(p.x, p.y)));
  });
  EXPECT_GT(checked, 200);
}

// A reader that makes a gradient texture of the size a name asks for
// ("4x2.png") and notes the paths it was asked for.
std::vector<std::string> g_read;
sol::Texture synthetic_reader(const std::string& path) {
  g_read.push_back(path);
  const std::string name = std::filesystem::path(path).filename().string();
  int w = 0, h = 0;
  if (std::sscanf(name.c_str(), "%dx%d", &w, &h) != 2) throw sol::InvalidArgument(path + ": no such file");
  return *gradient_texture(w, h);
}

TEST(Texture, SceneFilesNameTheImageRelativeToThemselves) {
  sol::set_texture_reader(synthetic_reader);
  g_read.clear();
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "sol_texture_test";
  std::filesystem::create_directories(dir);
  const std::string text = R"({"objects": [{"type": "plane_z", "c": -1, "texture": "4x2.png", "texture_cells": [2, 0.25]}]})";
  std::ofstream(dir / "scene.json") << text;
  const sol::Scene scene = sol::load_scene((dir / "scene.json").string());
  ASSERT_EQ(g_read.size(), 1u);
  EXPECT_EQ(std::filesystem::path(g_read[0]), dir / "4x2.png");
  ASSERT_TRUE(scene.objects[0].texture);
  EXPECT_EQ(scene.objects[0].texture->width, 4);
  EXPECT_EQ(scene.objects[0].texture->height, 2);
  EXPECT_EQ(scene.objects[0].texture_cells, glm::dvec2(2.0, 0.25));
  // Written back by its absolute path, read back the same from anywhere.
  EXPECT_EQ(std::filesystem::path(scene.objects[0].texture->file), dir / "4x2.png");
  const sol::Scene again = sol::parse_scene(sol::to_json(scene), "elsewhere");
  EXPECT_EQ(std::filesystem::path(again.objects[0].texture->file), dir / "4x2.png");
  EXPECT_EQ(again.objects[0].texture_cells, glm::dvec2(2.0, 0.25));
  std::filesystem::remove_all(dir);
}

TEST(Texture, ABadTextureIsRefusedByItsField) {
  sol::set_texture_reader(synthetic_reader);
  const auto refused = [](const std::string& object, const std::string& field, const std::string& says) {
    try {
      sol::parse_scene(R"({"objects": [)" + object + "]}", "test");
      ADD_FAILURE() << object << " accepted";
    } catch (const sol::InvalidArgument& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
    }
  };
  refused(R"({"type": "plane_z", "c": 0, "texture": "4x2.png", "texture_cells": [3, 1]})", "texture_cells", "power of two");
  refused(R"({"type": "plane_z", "c": 0, "texture": "4x2.png", "texture_cells": [128, 1]})", "texture_cells", "64");
  refused(R"({"type": "plane_z", "c": 0, "texture": "missing.png"})", "objects[0].texture", "no such file");
  refused(R"({"type": "plane_z", "c": 0, "texture": 3})", "objects[0].texture", "image file");
  sol::set_texture_reader({});
  refused(R"({"type": "plane_z", "c": 0, "texture": "4x2.png"})", "objects[0].texture", "reads no image files");
  // A texture's values are an albedo: in [0, 1].
  sol::Scene scene = sol::preset_scene("plane");
  auto t = std::make_shared<sol::Texture>(*gradient_texture(2, 2));
  t->rgb[4] = 1.5f;
  scene.objects[0].texture = t;
  EXPECT_THROW(sol::CpuRenderer{scene}, sol::InvalidArgument);
  // At most 8192 texels a side.
  auto wide = std::make_shared<sol::Texture>();
  wide->width = sol::Texture::kMaxTextureSize + 1;
  wide->height = 1;
  wide->rgb.assign(3 * static_cast<std::size_t>(wide->width), 0.5f);
  scene.objects[0].texture = wide;
  EXPECT_THROW(sol::CpuRenderer{scene}, sol::InvalidArgument);
  wide->width = sol::Texture::kMaxTextureSize;
  wide->rgb.resize(3 * static_cast<std::size_t>(wide->width));
  EXPECT_NO_THROW(sol::CpuRenderer{scene});
}

}  // namespace
