// The CPU reference ray-marcher: the same march and shading as the Vulkan
// kernels, in double precision, multi-threaded. The kernels are tested
// against it.
//
// The march (one ray per pixel, camera convention of DESIGN.md §2):
//  1. The scene is expressed relative to the camera (left-translation by the
//     camera position's inverse), so every ray starts at the origin; a plane
//     x = c becomes x = e^{-p_z}(c - p_x), y = c becomes y = e^{p_z}(c - p_y),
//     z = c becomes z = c - p_z.
//  2. Per ray, the closed-form geodesic is precomputed once
//     (ClosedFormGeodesic<double>); each step evaluates it at the accumulated
//     arc length t from the ray's origin, so no error accumulates from step
//     to step.
//  3. t advances by the exact distance to the nearest object (sol/distance.hpp);
//     the ray hits when that distance is below hit_epsilon, and misses when t
//     exceeds max_distance or the steps exceed max_steps. When every object
//     is a plane z = c, the march evaluates heights only, and a ray whose
//     whole z-range (between its turning points) misses every plane by more
//     than hit_epsilon is a miss at once (0 steps): an exact test.
// Shading: base colour times the pattern (in the plane's own world
// coordinates), times ambient + (1 - ambient) Σ_lights colour · intensity ·
// attenuation · max(0, n·l), n the unit gradient of the distance (frame
// components, facing the ray's side) and l the direction to the light
// (light_at); then exponential fog: mix(fog colour, colour, e^{-density t}).
// Misses are black.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "sol/scene.hpp"

namespace sol {

/// What a light contributes at a point p (world coordinates):
///  - directional: l = normalize(direction), attenuation 1;
///  - point: l = the coordinate difference to the light in frame components
///    at p, normalize(e^{-z}Δx, e^{z}Δy, Δz) (left-invariant, but not the
///    direction of the geodesic to the light: that comes in a later issue,
///    through this function), attenuation 1 / (1 + r²), r =
///    distance_lower_bound(p, light.position).
struct LightAtPoint {
  glm::dvec3 direction;  ///< unit, frame components at p, towards the light
  double attenuation;
};
LightAtPoint light_at(const Light& light, const glm::dvec3& p);

/// Every way a light reaches p. Exact point lights (Light::exact): one entry
/// per geodesic from p to the light up to distance + reach
/// (sol::geodesics_between; reach 0: the minimisers only, two on the cut
/// locus), l its unit direction at p, attenuation 1 / (1 + L²) with L its
/// length. Otherwise the single light_at.
std::vector<LightAtPoint> lights_at(const Light& light, const glm::dvec3& p);

/// The camera's orthonormal basis of DESIGN.md §2 (frame components):
/// right = normalize(forward × up), up' = right × forward.
struct CameraBasis {
  glm::dvec3 right, up, forward;
  double tan_half_fov;  ///< tan(fov / 2)
};
CameraBasis camera_basis(const Camera& camera);

/// The image's window on the plane one unit along forward, as
/// (s_x at the left edge, s_x at the right edge, s_y at the top edge, s_y at
/// the bottom edge): the centre of pixel (i, j) of a width × height image
/// looks along s_x·right + s_y·up + forward, s_x and s_y interpolated
/// linearly at (i + 0.5)/width and (j + 0.5)/height. Without a frustum
/// (DESIGN.md §2): (-t·width/height, t·width/height, t, -t), t = tan(fov/2);
/// with one: (left, right, up, down).
glm::dvec4 image_window(const Camera& camera, int width, int height);

/// An object as the march sees it, left-translated by origin⁻¹ (origin at the
/// identity: world coordinates): planes by their constant (x = e^{-z_o}(c - x_o),
/// y = e^{z_o}(c - y_o), z = c - z_o), balls by their centre, tubes by a point
/// of their axis and, for horizontal axes, the axis's unit coordinate
/// direction `heading` (left-translation maps lines to lines and scales a
/// horizontal direction (h_x, h_y) to (e^{-z_o} h_x, e^{z_o} h_y)).
/// The CPU renderer and the kernels' hosts share it.
struct MarchObject {
  ObjectType type = ObjectType::PlaneZ;
  double c = 0.0;
  glm::dvec3 center{0.0};
  double radius = 0.0;
  int axis = 2;              ///< tubes: 2 vertical, anything else horizontal along `heading`
  std::size_t owner = 0;     ///< index of the scene object
  glm::dvec2 heading{0.0};   ///< horizontal tubes: unit coordinate direction of the axis
  bool exact = false;        ///< balls: the exact distance near the ball (sol::sdf_ball_exact)
};
MarchObject relative_object(const SceneObject& object, const glm::dvec3& origin, std::size_t owner);
/// The same object left-translated by origin⁻¹ (from world coordinates to
/// coordinates relative to `origin`).
MarchObject relative_to(const MarchObject& object, const glm::dvec3& origin);

/// The signed distance (exact for planes, a lower bound for balls and
/// tubes: sol/distance.hpp) from q to an object in the same coordinates.
double object_distance(const MarchObject& object, const glm::dvec3& q);

/// Pattern coordinates (u, v) of a hit point q on an object given in the
/// same coordinates as q. Planes: their own world coordinates (pass world
/// coordinates). Balls: with w = centre⁻¹·q, (4/π)·longitude atan2(w_y, w_x)
/// and (4/π)·latitude atan2(w_z, |w_xy|) (8 cells around, 4 from pole to
/// pole). Tubes: with w = through⁻¹·q, (4/π)·the angle around the axis and
/// 4/(π r)·the coordinate along it (square cells of side πr/4 on the surface).
glm::dvec2 pattern_coordinates(const MarchObject& object, const glm::dvec3& q);

/// A lower bound of the distance from the world point w to the solid part of
/// a cutout plane z = c with `pattern` (its discs or light squares), to be
/// combined with |w_z - c| by max; 0 where it cannot help (on a light square,
/// pattern none). A point p of the plane at planar offset (Δx, Δy) from w is
/// at distance >= asinh(|Δx| e^{-z}) and >= asinh(|Δy| e^{z}) (the planes
/// x, y = const through p), z = w_z, so:
///  - checker, w over a dark square: the light squares nearest in both
///    senses share an edge with it: asinh(min(min(f_u, 1 - f_u) e^{-z}, min(f_v, 1 - f_v) e^{z}));
///  - circles: the nearest disc is the cell's own, inside the square
///    [0.2, 0.8]² of the cell: asinh(max(g_u e^{-z}, g_v e^{z})) with the gaps
///    g to that square's sides; and max(|Δx|e^{-z}, |Δy|e^{z}) >=
///    e^{-|z|}|Δ|/√2, so also asinh(e^{-|z|} g/√2), g the planar gap to the disc.
/// With it the march steps across the holes of a cutout instead of edging
/// through them by 2 hit_epsilon at a time.
double cutout_gap_bound(Pattern pattern, const glm::dvec3& w);

/// Quotient scenes: the images, in world coordinates, of the scene's objects
/// that a march step can reach from D. Each object is first moved by Γ so
/// that its centre or axis point lies in D; its images g·object, g =
/// γ1^a γ2^b γ3^c with |a|, |b| <= 10, |c| <= 1, are kept when a lower bound
/// of their distance bound over all of D is at most the longest step (0.5):
/// see the proof in render.cpp. Lines that coincide are listed once.
std::vector<MarchObject> quotient_images(const Scene& scene);

/// The longest march step in the quotient: no image beyond it is listed.
inline constexpr double kQuotientMaxStep = kernel::kQuotientMaxStep;

/// The ray through the centre of pixel (i, j) (row 0 at the top) of a
/// width × height image: unit direction in frame components at the camera.
glm::dvec3 camera_ray(const Camera& camera, int i, int j, int width, int height);

/// Result of marching one ray.
struct MarchHit {
  int object = 0;              ///< 0: no hit; k: the k-th object of the scene (1-based)
  double distance = 0.0;       ///< arc length to the hit (to where the march stopped on a miss)
  glm::dvec3 point{0.0};       ///< hit point, world coordinates
  glm::dvec3 normal{0.0};      ///< unit surface normal at the hit, frame components, facing the ray
  glm::dvec2 pattern_uv{0.0};  ///< the object's pattern coordinates at the hit (pattern_coordinates)
  int steps = 0;               ///< march steps used (0: culled by its height range)
};

/// Marches the ray from the camera position with unit direction `direction`
/// (frame components at the camera).
MarchHit march(const Scene& scene, const glm::dvec3& direction);

/// Linear RGB of a hit (black for a miss).
glm::dvec3 shade(const Scene& scene, const MarchHit& hit);

struct RenderSettings {
  int width = 512;
  int height = 512;
  unsigned threads = 0;  ///< 0: all hardware threads
  /// Called now and then from the calling thread with the finished fraction in [0, 1].
  std::function<void(double)> progress;
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

/// Renders the scene on the CPU. Throws InvalidArgument for an invalid scene
/// or sizes outside [1, 16384].
RenderResult render_cpu(const Scene& scene, const RenderSettings& settings);

/// The two eyes of DESIGN.md §2: at the geodesic flow of the camera by
/// ∓ipd/2 along its right vector, their frames (forward, up) parallel-
/// transported along that flow; same field of view. ipd must be finite and
/// >= 0 (InvalidArgument otherwise).
struct StereoEyes {
  Camera left, right;
};
StereoEyes stereo_eyes(const Camera& camera, double ipd);

/// Both eyes side by side in one image of width 2 × settings.width (left eye
/// on the left), AOVs likewise: each half is render_cpu of that eye's camera.
RenderResult render_cpu_stereo(const Scene& scene, const RenderSettings& settings, double ipd);

}  // namespace sol
