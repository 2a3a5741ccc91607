// The scene model: a world (objects, lights, fog, the space the rays live
// in, the march's limits) and the camera it is first seen from. Renderers
// prepare a world once (sol::CpuRenderer::set_world, sol::vk::MarchRenderer::
// set_world) and then render it from any cameras; a scene file holds both
// (sol/scene_file.hpp, docs/scene-format.md).
//
// All positions are Sol coordinates; all directions are frame components
// (docs/conventions.md).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "sol/camera.hpp"
#include "sol/display.hpp"
#include "sol/lattice.hpp"
#include "sol/light.hpp"
#include "sol/objects.hpp"
#include "sol/spaces.hpp"

namespace sol {


/// The most objects a world holds (World::objects): about 200 MB of scene
/// objects, a limit against runaway files rather than of the march, which
/// visits the objects of a large world through their tree of bounds
/// (sol/bounds_tree.hpp).
inline constexpr std::size_t kMaxObjects = std::size_t{1} << 20;
/// A Sol world of up to this many objects is marched through its list; a
/// larger one through its tree of bounds (sol::MarchWorld::tree), on the
/// CPU and the kernel alike (sol/kernel_constants.h).
inline constexpr std::size_t kListedObjects = static_cast<std::size_t>(kernel::kListedObjects);
/// A quotient's images stay a list (sol::QuotientField), so a quotient
/// world holds at most this many objects.
inline constexpr std::size_t kQuotientObjects = 64;

/// Everything that is seen, and how the march looks for it.
struct World {
  /// The space the rays live in (sol/spaces.hpp): Sol itself or a quotient
  /// Γ\Sol, where rays stay in the fundamental domain D and teleport back by
  /// an element of Γ: compact (the golden lattice's, a monodromy's torus
  /// bundle) or not (a z loop, xy loops: these allow balls, boxes, planes
  /// z = c and some tubes, docs/scene-format.md).
  Space space;
  std::vector<SceneObject> objects;      ///< at most kMaxObjects
  std::vector<Light> lights{Light{}};    ///< at most kMaxLights; default: one white directional light
  double ambient = 0.15;                 ///< light reaching surfaces facing away, in [0, 1]
  glm::dvec3 fog_color{0.0, 0.0, 0.0};   ///< exponential fog: colour = mix(fog_color, colour, e^{-density t})
  double fog_density = 0.0;              ///< per unit arc length, >= 0; 0 = no fog
  double max_distance = 30.0;            ///< arc length after which a ray misses
  int max_steps = 200;                   ///< march steps after which a ray misses
  double hit_epsilon = 5e-5;             ///< a ray hits when the distance falls below this
  /// How far light is followed from a camera ray's hit, in [0, 64]: in
  /// direct light the reflections a ray takes in mirrors (past them a
  /// mirror's share is black), in path tracing the scatterings a path takes
  /// (each a mirror's reflection or a diffuse bounce; 0: the hit's emission
  /// and the lights' light alone), as other path tracers' maximum depth.
  /// None: mirror_bounces() and path_bounces() give each its default.
  std::optional<int> max_bounces;

  /// Direct light's reflections in mirrors: max_bounces, else 4.
  int mirror_bounces() const { return max_bounces.value_or(kDefaultMirrorBounces); }
  /// A path's scatterings: max_bounces, else 64, where the furnace E / (1 − ρ)
  /// of a wall of albedo 0.6 misses 0.6^65 of its light and Russian roulette
  /// has ended nearly every path long before.
  int path_bounces() const { return max_bounces.value_or(kDefaultPathBounces); }
  static constexpr int kDefaultMirrorBounces = 4;
  static constexpr int kDefaultPathBounces = 64;

  /// Which space: Sol (Quotient::None) or which quotient.
  Quotient quotient() const { return quotient_of(space); }
  /// The lattice Γ of the quotient the rays live in (sol/lattice.hpp), or
  /// none in Sol itself: everything that teleports, lists images or binds an
  /// observer to the domain takes the world's lattice from here.
  std::optional<Lattice> lattice() const { return lattice_of(space); }
};

/// A world and the camera it is first seen from: what a scene file or a
/// preset holds. A Scene is a World (renderers take the world part).
struct Scene : World {
  Camera camera;
  /// Anti-aliasing samples per pixel a render of the scene takes (in [1,
  /// 4096]; RenderOptions::samples, solrender --spp overrides it).
  int samples = 1;
  /// How its 8-bit pictures show the linear image: exposure and tone curve
  /// (sol/display.hpp; solrender --exposure and --tone override them).
  Display display;
};

/// Whether two worlds live in the same space (the same quotient and parameters).
inline bool same_space(const World& a, const World& b) { return a.space == b.space; }

/// Moves the world into another space. Tubes along the old lattice's γ1 or
/// γ2 (the golden one's in Sol) turn to the new lattice's, so that the
/// closed curves stay closed curves. Throws what the space's lattice() throws
/// for a bad parameter (a monodromy that is not hyperbolic), the world unchanged.
void set_space(World& world, const Space& space);

/// Checks every field of the world (finite numbers, positive limits,
/// colours in [0, 1], at least one object, at most 64 objects and
/// kMaxLights lights, what the quotient allows); throws InvalidArgument
/// naming the field.
void validate(const World& world);
/// The world and the camera (sol::validate(const Camera&)).
void validate(const Scene& scene);

/// Whether the world has exact balls or exact point lights (these need the
/// connection solver, sol/connection.hpp, or its tables in the kernels).
bool uses_exact(const World& world);
/// Whether the world has exact point lights.
bool uses_exact_lights(const World& world);

/// Built-in scenes: "plane" (z = 0 tiled with circles, seen from (0,0,1.5)
/// looking straight down), "sandwich" (planes z = ±1, observer at the
/// origin), "sheets" (planes x = 0 and y = 0), "lattice-balls" (Γ\Sol, one
/// ball at the base point), "lattice-pillars" (Γ\Sol, tubes along the closed
/// curves of γ1, γ2, γ3 through the base point), "lattice-boxes" (Γ\Sol, one
/// cube at the base point), "trace4-balls" and "trace4-pillars" (the same
/// in the torus bundle of [[3, 1], [2, 1]]), "halfturn-balls" (the bundle of
/// [[-2, -1], [-1, -1]], whose γ3 turns the fibre: a ball at the base point
/// and one off it), "spheres" (exact geodesic
/// spheres of several radii above, on and below z = 0, lit by an exact point
/// light). InvalidArgument if unknown.
Scene preset_scene(std::string_view name);
std::vector<std::string> preset_names();

}  // namespace sol
