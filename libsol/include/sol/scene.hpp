// Scene description: camera, objects, light, fog and march limits, read from
// JSON (README "Scene files" documents the schema) or taken from a preset.
//
// All positions are Sol coordinates; all directions are frame components
// (DESIGN.md §2). A light direction is constant in the left-invariant frame,
// so it means the same everywhere.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "sol/kernel_constants.h"

namespace sol {

enum class ObjectType {
  PlaneX,  ///< the plane x = c (a totally geodesic hyperbolic plane)
  PlaneY,  ///< the plane y = c
  PlaneZ,  ///< the plane z = c (a flat horizontal plane)
  Ball,    ///< the points within `radius` of `center`, drawn with a distance bound (README)
  Tube,    ///< the points within `radius` of the line through `center` along `axis` (a bound; README)
};

enum class Pattern {
  None,     ///< plain base colour
  Circles,  ///< discs of radius 0.3 centred on the unit grid of the plane's own coordinates
  Checker,  ///< unit checkerboard in the plane's own coordinates
};

/// The axis of a tube: a coordinate line, or the horizontal line along γ1 =
/// (φ, -1, 0) or γ2 = (1, φ, 0) (the one-parameter subgroups t·γ1, t·γ2 of the
/// plane z = 0, translated): through a point of Γ·o these are the closed
/// curves of γ1, γ2 in M = Γ\Sol, and the z-line is the closed curve of γ3.
enum TubeAxis : int { kAxisX = 0, kAxisY = 1, kAxisZ = 2, kAxisGamma1 = 3, kAxisGamma2 = 4 };

/// Unit coordinate direction of a tube axis: (1,0,0), (0,1,0), (0,0,1),
/// (φ,-1,0)/|.|, (1,φ,0)/|.|. Every axis but z is horizontal.
glm::dvec3 tube_axis_direction(int axis);

/// Largest radius of a ball or tube in a quotient scene: the images of the
/// objects are listed for the cells next to D only (sol::quotient_images),
/// which holds while h - radius exceeds the longest quotient step (0.5).
constexpr double kMaxQuotientRadius = 0.45;

struct SceneObject {
  ObjectType type = ObjectType::PlaneZ;
  double c = 0.0;                      ///< planes: the constant coordinate
  glm::dvec3 color{0.8, 0.8, 0.8};     ///< linear RGB in [0, 1]
  Pattern pattern = Pattern::None;     ///< planes: in their own coordinates; balls, tubes: see sol/render.hpp
  bool cutout = false;                 ///< planes: only the pattern's bright cells (discs, light squares) are solid
  glm::dvec3 center{0.0, 0.0, 0.0};    ///< balls: centre (Sol coordinates)
  double radius = 0.5;                 ///< balls, tubes: radius, > 0
  int axis = 2;                        ///< tubes: a TubeAxis (the line through `center`)
  bool exact = false;                  ///< balls: draw the true geodesic sphere (sol::sdf_ball_exact), not the bound
};

enum class LightType {
  Directional,  ///< from `direction` (frame components: the same at every point)
  Point,        ///< from `position` (see sol/render.hpp for the direction and attenuation used)
};

struct Light {
  LightType type = LightType::Directional;
  glm::dvec3 direction{0.3, 0.5, 1.0};  ///< directional: towards the light (normalised on use)
  glm::dvec3 position{0.0, 0.0, 0.0};   ///< point: Sol coordinates
  glm::dvec3 color{1.0, 1.0, 1.0};      ///< linear RGB in [0, 1]
  double intensity = 1.0;               ///< >= 0
  /// point: light along the true geodesics to the light (sol::geodesics_between),
  /// each attenuated by its length, instead of the coordinate direction
  bool exact = false;
  double reach = 0.0;  ///< exact point lights: also the connections up to distance + reach, in [0, 10]
};

/// Most lights a scene may hold (a limit the kernels share).
using kernel::kMaxLights;

/// An off-axis view window (a headset eye's): the tangents of the angles
/// from `forward` to the image's left, right, bottom and top edges, measured
/// towards right and up (so left < right, down < up; OpenXR's XrFovf gives
/// tan(angleLeft), tan(angleRight), tan(angleDown), tan(angleUp)).
struct Frustum {
  double left = -1.0, right = 1.0, down = -1.0, up = 1.0;
};

struct Camera {
  glm::dvec3 position{0.0, 0.0, 0.0};
  glm::dvec3 forward{1.0, 0.0, 0.0};  ///< frame components at position
  glm::dvec3 up{0.0, 0.0, 1.0};       ///< frame components; not parallel to forward
  double fov = 60.0;                  ///< vertical field of view, degrees, in (0, 180)
  /// When set, the image spans this window instead of the centred one of
  /// `fov` and the image's aspect ratio (sol::image_window).
  std::optional<Frustum> frustum;
};

/// The space the rays live in: Sol itself, or the compact quotient Γ\Sol
/// of the golden lattice (sol/lattice.hpp), where rays stay in the
/// fundamental domain D and teleport back by an element of Γ.
enum class Quotient { None, Golden };

struct Scene {
  Camera camera;
  Quotient quotient = Quotient::None;
  std::vector<SceneObject> objects;
  std::vector<Light> lights{Light{}};           ///< at most kMaxLights; default: one white directional light
  double ambient = 0.15;                       ///< light reaching surfaces facing away, in [0, 1]
  glm::dvec3 fog_color{0.0, 0.0, 0.0};         ///< exponential fog: colour = mix(fog_color, colour, e^{-density t})
  double fog_density = 0.0;                    ///< per unit arc length, >= 0; 0 = no fog
  double max_distance = 30.0;                  ///< arc length after which a ray misses
  int max_steps = 200;                         ///< march steps after which a ray misses
  double hit_epsilon = 5e-5;                   ///< a ray hits when the distance falls below this
};

/// Checks every field (finite numbers, non-zero and non-parallel camera
/// vectors, fov in (0, 180), positive limits, colours in [0, 1], at least
/// one object); throws InvalidArgument naming the field.
void validate(const Scene& scene);

/// Parses a scene from JSON text; `source` (a file name) prefixes every error
/// message. Unknown keys are errors (a typo must not pass silently). Throws
/// InvalidArgument on malformed or inconsistent input.
Scene parse_scene(std::string_view json, std::string_view source = "<scene>");

/// Reads and parses a scene file; InvalidArgument if unreadable or invalid.
Scene load_scene(const std::string& path);

/// Whether the scene has exact balls or exact point lights: these need the
/// connection solver (sol/connection.hpp), which only the CPU renderer runs.
bool uses_exact(const Scene& scene);
/// Whether the scene has exact point lights (the kernel has exact balls, from
/// a table, but no exact lights).
bool uses_exact_lights(const Scene& scene);

/// Built-in scenes: "plane" (z = 0 tiled with circles, seen from (0,0,1.5)
/// looking straight down), "sandwich" (planes z = ±1, observer at the
/// origin), "sheets" (planes x = 0 and y = 0), "lattice-balls" (Γ\Sol, one
/// ball at the base point), "lattice-pillars" (Γ\Sol, tubes along the closed
/// curves of γ1, γ2, γ3 through the base point), "spheres" (exact geodesic
/// spheres of several radii above, on and below z = 0, lit by an exact point
/// light). InvalidArgument if unknown.
Scene preset_scene(std::string_view name);
std::vector<std::string> preset_names();

/// Scene as JSON text in the documented schema (parse_scene reads it back).
std::string to_json(const Scene& scene);

const char* to_string(ObjectType type);
const char* to_string(Pattern pattern);

}  // namespace sol
