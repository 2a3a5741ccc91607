// Image textures: an object's colour times an image's, placed by the
// object's pattern coordinates (sol/texture.h has the mapping). libsol
// decodes no image files: a program installs the reader that does
// (sol::programs::install_texture_reader, OpenImageIO, in the programs and
// the Python module), and scene files' "texture" keys go through it:
//
//   sol::set_texture_reader([](const std::string& path) { ... decode ... });
//   sol::Scene scene = sol::load_scene("world.json");   // "texture": "stone.png"
//
// or a program builds a Texture itself (SceneObject::texture).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace sol {

/// An image in linear RGB, row 0 at the top: what the object's colour is
/// multiplied by (a file's sRGB values are decoded, its alpha ignored).
struct Texture {
  std::string file;          ///< the image file's absolute path (written back by sol::to_json), or a name
  int width = 0, height = 0;  ///< in [1, kMaxTextureSize]
  std::vector<float> rgb;    ///< 3 per texel: an albedo, in [0, 1]
  /// The largest side: an image of 8192² texels holds 0.8 GB of floats
  /// here and 1 GB on the kernel (a vec4 a texel), the most a still needs.
  static constexpr int kMaxTextureSize = 8192;
};

/// The fewest and most pattern cells one copy of an image may span along
/// u or v (SceneObject::texture_cells); a power of two between them, so
/// that the kernel's pattern phase (the eye's position modulo
/// kTexturePhase) keeps every copy's place.
inline constexpr double kMinTextureCells = 1.0 / 16.0;
inline constexpr double kMaxTextureCells = 64.0;
inline constexpr double kTexturePhase = 64.0;

/// Reads the image file `path` into a Texture (its `file` set by the
/// caller); throws sol::InvalidArgument naming the file and why.
using TextureReader = std::function<Texture(const std::string& path)>;

/// The process's reader (replacing any before; empty: none).
void set_texture_reader(TextureReader reader);
/// Whether one is installed.
bool has_texture_reader();
/// The image at `path` through the installed reader, checked
/// (validate_texture), its `file` = `named` (the scene file's reader gives
/// the absolute path); InvalidArgument without a reader.
std::shared_ptr<const Texture> read_texture(const std::string& path, const std::string& named);

/// The checks of a texture: its size, its values; InvalidArgument naming `field`.
void validate_texture(const Texture& texture, const std::string& field);
/// The checks of texture cells: each a power of two in [kMinTextureCells, kMaxTextureCells].
void validate_texture_cells(const glm::dvec2& cells, const std::string& field);

/// The image's colour at pattern coordinates `uv` spread over `cells`
/// (sol::kernel::sol_texture_taps, bilinear), in double.
glm::dvec3 texture_color(const Texture& texture, const glm::dvec2& cells, const glm::dvec2& uv);

}  // namespace sol
