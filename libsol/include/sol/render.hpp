// The CPU reference ray-marcher: the same march and shading as the Vulkan
// kernels, in double precision, multi-threaded. The kernels are tested
// against it.
//
// A renderer holds a world prepared once (set_world: validation, features,
// the quotient's images) and renders it from any camera:
//
//   sol::CpuRenderer renderer(scene);                // a Scene is a World
//   sol::RenderResult image = renderer.render(scene.camera, {.width = 256, .height = 256});
//
// It is a sol::Renderer (sol/renderer.hpp), as the Vulkan kernel's is.
//
// The march (one ray per pixel, sol/camera.hpp; sol/march.hpp describes it):
//  1. The world is expressed relative to the camera (left-translation by the
//     camera position's inverse), so every ray starts at the origin.
//  2. Per ray, the closed-form geodesic is precomputed once
//     (ClosedFormGeodesic<double>); each step evaluates it at the accumulated
//     arc length t from the ray's origin, so no error accumulates from step
//     to step.
//  3. t advances by the distance to the nearest object (a lower bound, exact
//     for planes); the ray hits when that distance is below hit_epsilon, and
//     misses when t exceeds max_distance or the steps exceed max_steps. When
//     every object is a plane z = c, the march evaluates heights only, and a
//     ray whose whole z-range (between its turning points) misses every
//     plane by more than hit_epsilon is a miss at once (0 steps): an exact test.
// Shading: base colour times the pattern (in the plane's own world
// coordinates), times ambient + (1 - ambient) Σ_lights colour · intensity ·
// attenuation · max(0, n·l), n the unit surface normal (frame components,
// facing the ray's side) and l the direction to the light (sol/light.hpp);
// then exponential fog: mix(fog colour, colour, e^{-density t}). Misses are black.
#pragma once

#include <memory>
#include <span>
#include <string>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "sol/camera.hpp"
#include "sol/march.hpp"
#include "sol/renderer.hpp"
#include "sol/scene.hpp"

namespace sol {

/// Result of marching one ray.
struct MarchHit {
  int object = 0;              ///< 0: no hit; k: the k-th object of the scene (1-based)
  double distance = 0.0;       ///< arc length to the hit (to where the march stopped on a miss)
  glm::dvec3 point{0.0};       ///< hit point, world coordinates
  glm::dvec3 normal{0.0};      ///< unit surface normal at the hit, frame components, facing the ray
  bool inside = false;         ///< the ray met a solid's surface from within it (its outward normal along the ray)
  glm::dvec2 pattern_uv{0.0};  ///< the object's pattern coordinates at the hit (sol::shape_pattern_uv)
  glm::dvec3 direction{0.0};   ///< the ray's unit tangent at the hit, frame components (a mirror reflects it)
  int steps = 0;               ///< march steps used (0: culled by its height range)
  /// The march stopped at the world's max_steps before it met an object or
  /// reached max_distance: what lies beyond is unknown (drawn as a miss,
  /// counted in RenderResult::out_of_steps).
  bool out_of_steps = false;
};

/// The CPU reference renderer (sol::Renderer): double precision, the
/// rows spread over threads.
class CpuRenderer final : public Renderer {
 public:
  /// A renderer with no world yet (set_world before rendering).
  CpuRenderer();
  /// set_world(world).
  explicit CpuRenderer(const World& world);
  ~CpuRenderer() override;
  CpuRenderer(CpuRenderer&&) noexcept;
  CpuRenderer& operator=(CpuRenderer&&) noexcept;

  /// Prepares the world once for every later render: validates it
  /// (InvalidArgument naming the field), finds its features and, in the
  /// quotient, its objects' images around D. Safe while another thread
  /// renders: that render finishes with the world it started with (each
  /// render, march and shade takes the world as it is when it starts).
  void set_world(const World& world) override;
  /// The same with a world prepared already (for instance through its list
  /// beyond sol::kListedObjects, to compare the two marches).
  void set_world(std::shared_ptr<const MarchWorld> prepared);
  /// The prepared world (logic_error before set_world), valid until the
  /// next set_world.
  const MarchWorld& world() const override;

  /// Renders the world from each eye (sol::Renderer::render); any number of
  /// eyes, each marched on its own and placed side by side.
  RenderResult render(std::span<const Camera> eyes, const RenderOptions& options) override;
  using Renderer::render;
  /// "cpu (N threads)", N the hardware's (RenderOptions::threads may use fewer).
  std::string description() const override;

  /// Marches the ray from the camera with unit direction `direction` (frame
  /// components at the camera). Validates the camera.
  MarchHit march(const Camera& camera, const glm::dvec3& direction) const;
  /// Linear RGB of a hit (black for a miss).
  glm::dvec3 shade(const MarchHit& hit) const;

 private:
  static RenderResult render_eye(const MarchWorld& prepared, const Camera& camera, const RenderOptions& options);
  std::shared_ptr<const MarchWorld> current_world() const;
  struct Held;
  std::unique_ptr<Held> m_held;
};

/// One-shot forms for a scene (its world seen from its camera), preparing
/// the world each call: CpuRenderer(scene).march(scene.camera, direction), ...
MarchHit march(const Scene& scene, const glm::dvec3& direction);
glm::dvec3 shade(const Scene& scene, const MarchHit& hit);
/// render_scene(CpuRenderer, scene, options) (sol/renderer.hpp).
RenderResult render_cpu(const Scene& scene, const RenderOptions& options);
/// Both eyes of sol::stereo_eyes(scene.camera, ipd) side by side, on the CPU.
RenderResult render_cpu_stereo(const Scene& scene, const RenderOptions& options, double ipd);

}  // namespace sol
