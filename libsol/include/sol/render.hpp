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

#include <atomic>
#include <functional>
#include <memory>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "sol/camera.hpp"
#include "sol/march.hpp"
#include "sol/scene.hpp"

namespace sol {

/// Result of marching one ray.
struct MarchHit {
  int object = 0;              ///< 0: no hit; k: the k-th object of the scene (1-based)
  double distance = 0.0;       ///< arc length to the hit (to where the march stopped on a miss)
  glm::dvec3 point{0.0};       ///< hit point, world coordinates
  glm::dvec3 normal{0.0};      ///< unit surface normal at the hit, frame components, facing the ray
  glm::dvec2 pattern_uv{0.0};  ///< the object's pattern coordinates at the hit (sol::shape_pattern_uv)
  int steps = 0;               ///< march steps used (0: culled by its height range)
};

struct RenderSettings {
  int width = 512;
  int height = 512;
  unsigned threads = 0;  ///< 0: all hardware threads
  /// Samples per pixel, >= 1: the colour is their mean (anti-aliasing, at
  /// sol::pixel_sample 0, 1, ...; a box filter over the pixel); the AOVs
  /// are the pixel centre's (sample 0).
  int samples = 1;
  /// Called now and then from the calling thread with the finished fraction in [0, 1].
  std::function<void(double)> progress;
  /// When set and true, the render stops within a row and throws sol::Cancelled.
  const std::atomic<bool>* cancel = nullptr;
};

/// An image and its arbitrary output variables, row-major, row 0 at the top.
struct RenderResult {
  int width = 0, height = 0;
  std::vector<float> rgba;      ///< 4 per pixel, linear RGB, alpha 1
  std::vector<float> object;    ///< per pixel: 0 = no hit, k = k-th object (1-based)
  std::vector<float> distance;  ///< arc length to the hit (0 on a miss)
  std::vector<float> px, py, pz;  ///< hit point, world Sol coordinates (0 on a miss)
  std::vector<float> steps;     ///< march steps used
};

class CpuRenderer {
 public:
  /// A renderer with no world yet (set_world before rendering).
  CpuRenderer();
  /// set_world(world).
  explicit CpuRenderer(const World& world);
  ~CpuRenderer();
  CpuRenderer(CpuRenderer&&) noexcept;
  CpuRenderer& operator=(CpuRenderer&&) noexcept;

  /// Prepares the world once for every later render: validates it
  /// (InvalidArgument naming the field), finds its features and, in the
  /// quotient, its objects' images around D.
  void set_world(const World& world);
  /// The prepared world (logic_error before set_world).
  const MarchWorld& world() const;

  /// Marches the ray from the camera with unit direction `direction` (frame
  /// components at the camera). Validates the camera.
  MarchHit march(const Camera& camera, const glm::dvec3& direction) const;
  /// Linear RGB of a hit (black for a miss).
  glm::dvec3 shade(const MarchHit& hit) const;

  /// Renders the world from `camera`. Throws InvalidArgument for an invalid
  /// camera or sizes outside [1, 16384].
  RenderResult render(const Camera& camera, const RenderSettings& settings) const;
  /// Both eyes of sol::stereo_eyes(camera, ipd) side by side in one image
  /// of width 2 × settings.width (left eye on the left), AOVs likewise.
  RenderResult render_stereo(const Camera& camera, const RenderSettings& settings, double ipd) const;

 private:
  std::unique_ptr<MarchWorld> m_world;
};

/// One-shot forms for a scene (its world seen from its camera), preparing
/// the world each call: CpuRenderer(scene).march(scene.camera, direction), ...
MarchHit march(const Scene& scene, const glm::dvec3& direction);
glm::dvec3 shade(const Scene& scene, const MarchHit& hit);
RenderResult render_cpu(const Scene& scene, const RenderSettings& settings);
RenderResult render_cpu_stereo(const Scene& scene, const RenderSettings& settings, double ipd);

}  // namespace sol
