// Lights: what they are in a scene, and how each reaches a point of a surface.
//
// A directional light shines from a direction that is constant in the
// left-invariant frame, so it means the same everywhere. A point light
// shines from a position; by default along the coordinate difference in
// frame components (an approximation), with "exact" along the true
// geodesics from the surface point to the light (sol::geodesics_between).
// docs/renderer.md "Lights" compares the two.
#pragma once

#include <limits>
#include <vector>

#include <glm/vec3.hpp>

#include "sol/kernel_constants.h"
#include "sol/lattice.hpp"

namespace sol {

enum class LightType {
  Directional,  ///< from `direction` (frame components: the same at every point)
  Point,        ///< from `position` (see light_at and lights_at for direction and attenuation)
};

/// How a point light's irradiance falls off along the way (docs/lighting.md).
enum class Falloff {
  Auto,           ///< Geodesic for exact lights, InverseSquare otherwise
  Geodesic,       ///< I / J(v, L): the true spreading of the geodesics (sol::sphere_area_density); exact lights only
  InverseSquare,  ///< I / (1 + L²) with L the geodesic's length (or the distance bound): a made-up law, for comparison
};

struct Light {
  LightType type = LightType::Directional;
  glm::dvec3 direction{0.3, 0.5, 1.0};  ///< directional: towards the light (normalised on use)
  glm::dvec3 position{0.0, 0.0, 0.0};   ///< point: Sol coordinates
  glm::dvec3 color{1.0, 1.0, 1.0};      ///< linear RGB in [0, 1]
  /// >= 0. Directional: the irradiance on a surface facing the light.
  /// Point: the radiant intensity I = Φ / 4π (power per steradian); with
  /// the geodesic falloff a surface facing the light receives I / J, which
  /// is I at unit area density (J = 1, about arc length 1).
  double intensity = 1.0;
  /// point: light along the true geodesics to the light (sol::geodesics_between),
  /// each attenuated by its length, instead of the coordinate direction
  bool exact = false;
  double reach = 0.0;  ///< exact point lights: also the connections up to distance + reach, in [0, 10]
  Falloff falloff = Falloff::Auto;  ///< point lights; Geodesic needs `exact`
  /// Exact point lights: objects between a hit point and the light block
  /// it. Each geodesic the light arrives along is marched from the hit point
  /// to the light against the scene (docs/lighting.md "Shadows"). Not for
  /// directional lights: their direction is a field, not the geodesics
  /// from a source (the geodesic along it comes back down: z oscillates).
  bool shadows = false;
};

/// The falloff a light uses: its own, Auto resolved (Geodesic for exact point lights).
Falloff falloff_of(const Light& light);

/// Most lights a scene may hold (a limit the kernels share).
using kernel::kMaxLights;

/// What a light contributes at a point p (world coordinates):
///  - directional: l = normalize(direction), attenuation 1;
///  - point: l = the coordinate difference to the light in frame components
///    at p, normalize(e^{-z}Δx, e^{z}Δy, Δz) (left-invariant, but not the
///    direction of the geodesic to the light: lights_at has that for exact
///    lights), attenuation 1 / (1 + r²), r = distance_lower_bound(p, light.position).
struct LightAtPoint {
  glm::dvec3 direction;  ///< unit, frame components at p, towards the light
  double attenuation;
  /// The arc length to the light along the geodesic leaving p along
  /// `direction` (an exact point light's connection); infinity for
  /// directional lights and approximate point lights (no such geodesic).
  double length = std::numeric_limits<double>::infinity();
};
LightAtPoint light_at(const Light& light, const glm::dvec3& p);

/// Every way a light reaches p. Exact point lights (Light::exact): one entry
/// per geodesic from p to the light up to distance + reach
/// (sol::geodesics_between; reach 0: the minimisers only, two on the cut
/// locus), l its unit direction at p, attenuation 1 / clamped_spreading(J)
/// with J = sphere_area_density(l, L) (the geodesic falloff: J seen from p
/// equals J seen from the light, reciprocity) or 1 / (1 + L²) (inverse
/// square), L its length. Otherwise the single light_at.
std::vector<LightAtPoint> lights_at(const Light& light, const glm::dvec3& p);

/// The compact quotient Γ\Sol: an exact point light at L is seen from p
/// along the geodesics to every image γ·L (γ ∈ Γ) of length up to
/// d + reach, d = min over γ of d(p, γ·L) (the distance in the quotient).
/// quotient_light_images lists the images that can matter from some point
/// of the fundamental domain D: L moved into D (L0), then every γ·L0 whose
/// distance from D can be at most R = C + reach, C an upper bound of the
/// distance from any point of D to its nearest image (computed: the
/// largest over a 7³ grid of D of the least distance to the images with
/// |a|, |b| <= 2, |c| <= 1, plus 0.87, the longest path from a point of D
/// to its nearest grid node; docs/lighting.md). Throws InvalidArgument, with
/// the largest reach the light allows, where images beyond the lattice
/// words enumerated (those of the objects' images) would lie within R.
std::vector<glm::dvec3> quotient_light_images(const Light& light, const Lattice& lattice);

/// lights_at in the quotient, p in D, `images` from quotient_light_images:
/// the images in order of their distance lower bound from p, their exact
/// distances while the bound is within the least so far + reach, then each
/// near image's connections as lights_at takes them (reach 0: the
/// minimisers of the images at the least distance).
std::vector<LightAtPoint> lights_at(const Light& light, const glm::dvec3& p, const std::vector<glm::dvec3>& images);

}  // namespace sol
