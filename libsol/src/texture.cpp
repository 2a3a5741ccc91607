#include "sol/texture.hpp"

#include <cmath>
#include <mutex>
#include <string>

#include <glm/vec4.hpp>

#include "sol/error.hpp"
#include "sol/texture.h"

namespace sol {
namespace {

std::mutex g_reader_mutex;
TextureReader g_reader;

}  // namespace

void set_texture_reader(TextureReader reader) {
  const std::lock_guard lock(g_reader_mutex);
  g_reader = std::move(reader);
}

bool has_texture_reader() {
  const std::lock_guard lock(g_reader_mutex);
  return static_cast<bool>(g_reader);
}

std::shared_ptr<const Texture> read_texture(const std::string& path, const std::string& named) {
  TextureReader reader;
  {
    const std::lock_guard lock(g_reader_mutex);
    reader = g_reader;
  }
  if (!reader) {
    throw InvalidArgument("texture '" + named + "': this program reads no image files (sol::set_texture_reader)");
  }
  Texture t = reader(path);
  t.file = named;
  validate_texture(t, "texture '" + named + "'");
  return std::make_shared<const Texture>(std::move(t));
}

void validate_texture(const Texture& t, const std::string& field) {
  if (t.width < 1 || t.height < 1 || t.width > Texture::kMaxTextureSize || t.height > Texture::kMaxTextureSize) {
    throw InvalidArgument(field + ": the image's size " + std::to_string(t.width) + " x " + std::to_string(t.height) +
                          " must be from 1 to " + std::to_string(Texture::kMaxTextureSize) + " each way");
  }
  if (t.rgb.size() != 3 * static_cast<std::size_t>(t.width) * static_cast<std::size_t>(t.height)) {
    throw InvalidArgument(field + ": " + std::to_string(t.rgb.size()) + " values for " + std::to_string(t.width) +
                          " x " + std::to_string(t.height) + " RGB texels");
  }
  for (const float v : t.rgb) {
    if (!(v >= 0.0f && v <= 1.0f)) {
      throw InvalidArgument(field + ": a texel value " + std::to_string(v) + " (an albedo: in [0, 1])");
    }
  }
}

void validate_texture_cells(const glm::dvec2& cells, const std::string& field) {
  for (int a = 0; a < 2; ++a) {
    const double c = cells[a];
    int exponent = 0;
    const bool power_of_two = std::isfinite(c) && c > 0.0 && std::frexp(c, &exponent) == 0.5;
    if (!power_of_two || c < kMinTextureCells || c > kMaxTextureCells) {
      char message[256];
      std::snprintf(message, sizeof message, "%s[%d]: %g pattern cells must be a power of two from 1/16 to 64", field.c_str(),
                    a, c);
      throw InvalidArgument(message);
    }
  }
}

glm::dvec3 texture_color(const Texture& t, const glm::dvec2& cells, const glm::dvec2& uv) {
  glm::ivec4 texels;
  glm::dvec2 along;
  kernel::sol_texture_taps(uv, cells, t.width, t.height, texels, along);
  auto at = [&](int i, int j) {
    const std::size_t k = 3 * (static_cast<std::size_t>(j) * static_cast<std::size_t>(t.width) + static_cast<std::size_t>(i));
    return glm::dvec3(t.rgb[k], t.rgb[k + 1], t.rgb[k + 2]);
  };
  const glm::dvec3 top = at(texels.x, texels.y) * (1.0 - along.x) + at(texels.z, texels.y) * along.x;
  const glm::dvec3 bottom = at(texels.x, texels.w) * (1.0 - along.x) + at(texels.z, texels.w) * along.x;
  return top * (1.0 - along.y) + bottom * along.y;
}

}  // namespace sol
