// The march's description of a world, shared by the CPU renderer
// (sol/render.hpp) and the kernels' host (sol::vk::MarchRenderer): the
// objects as the march sees them, their images around the fundamental
// domain in the quotient, and the bounds that let a ray step across the
// holes of cutout planes. A MarchWorld is prepared once per world; per
// camera only the objects' left-translation changes (MarchWorld::seen_from).
//
// The march itself (docs/renderer.md): every ray starts at the camera, whose
// inverse left-translates the world so that the ray starts at the origin; its
// closed-form geodesic is evaluated at the accumulated arc length t, and t
// advances by the distance to the nearest object (a lower bound, exact for
// planes) until that falls below hit_epsilon (a hit) or t passes
// max_distance or the steps max_steps (a miss). In the quotient the ray
// lives in D, teleports back by an element of Γ when it leaves it, and
// steps by the world's distance field (sol/quotient_field.hpp).
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "sol/bounds_tree.hpp"
#include "sol/kernel_constants.h"
#include "sol/march_features.h"
#include "sol/objects.hpp"
#include "sol/scene.hpp"

namespace sol {

/// A scene object as the march sees it: its shape in the march's
/// coordinates (world coordinates, or relative to an origin: see
/// shape_seen_from) and which scene object it comes from.
struct MarchObject {
  Shape shape;
  std::size_t owner = 0;  ///< index of the scene object
};

/// The same object left-translated by origin⁻¹ (from world coordinates to
/// coordinates relative to `origin`).
MarchObject relative_to(const MarchObject& object, const glm::dvec3& origin);

/// The signed distance (exact for planes, a lower bound for balls and
/// tubes: sol/distance.hpp) from q to an object in the same coordinates.
double object_distance(const MarchObject& object, const glm::dvec3& q);

/// How far the geodesic from q with unit tangent u (frame components) goes
/// before it can reach the object (sol/clearance.hpp): a safe step, longer
/// than the bound beside the surface. For exact balls it is the bound's
/// ball's; a march steps by the larger of it and object_distance.
double object_clearance(const MarchObject& object, const glm::dvec3& q, const glm::dvec3& u);
/// object_clearance ahead along u and back along −u (sol::shape_clearances).
Clearances object_clearances(const MarchObject& object, const glm::dvec3& q, const glm::dvec3& u);

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

/// The longest march step in the quotient: no image beyond it is listed.
inline constexpr double kQuotientMaxStep = kernel::kQuotientMaxStep;
/// The longest step of a world whose images within kQuotientMaxStep of D
/// would be more than kQuotientLongStepImages (sol::quotient_max_step).
inline constexpr double kQuotientShortStep = 0.5;
inline constexpr std::size_t kQuotientLongStepImages = 64;
// kLatticeHeight, 2 ln φ, is the least height of any lattice (ln λ for
// the least |trace| of a hyperbolic monodromy, 3).
static_assert(kQuotientShortStep < kQuotientMaxStep && kQuotientMaxStep < kernel::kLatticeHeight,
              "a quotient step from D must end within one layer of cells of it");

/// Quotient worlds: the images, in world coordinates, of the world's objects
/// that a march step of at most `max_step` (<= kQuotientMaxStep) can reach
/// from D. Each object is first moved by Γ so that its centre or axis point
/// lies in D; its images g·object, g = γ1^a γ2^b γ3^c over the words whose
/// image of that point (or axis) can come within max_step +
/// kMaxQuotientRadius of D, are kept when a lower bound of their distance
/// bound over all of D is at most max_step: see the proof in march.cpp.
/// Lines that coincide are listed once.
std::vector<MarchObject> quotient_images(const World& world, double max_step);
/// The images for the world's own longest step (quotient_max_step).
std::vector<MarchObject> quotient_images(const World& world);

/// The longest march step of a quotient world: kQuotientMaxStep, or
/// kQuotientShortStep where more than kQuotientLongStepImages images lie
/// within kQuotientMaxStep of D (long steps list many images: the kernel
/// takes at most kMaxGpuImages, and every one costs the distance field's
/// construction time).
double quotient_max_step(const World& world);

/// What a world uses, for the march's short cuts and the kernels'
/// specialisation constants: a flag per line of SOL_MARCH_FEATURES
/// (sol/march_features.h, which says what each means), and the CPU's own.
struct MarchFeatures {
#define SOL_FEATURE_MEMBER(member, constant, id) bool member = false;
  SOL_MARCH_FEATURES(SOL_FEATURE_MEMBER)
#undef SOL_FEATURE_MEMBER
  bool cutout_gaps = false;  ///< cutout planes z = c: their gap bounds need the full position (the CPU's march)
};
MarchFeatures features_of(const World& world);

class QuotientField;

/// What makes a quotient world's objects fewer images around the domain,
/// for the messages that refuse a crowded one: "(fewer or smaller
/// objects, ...)", with what else helps in its kind of quotient.
std::string crowded_quotient_hint(const World& world);

/// A world prepared for the march once: checked, its features found, its
/// objects in world coordinates (Sol) or their images around D and their
/// distance field (the quotient: sol::quotient_images, sol::QuotientField).
/// What depends on the camera is not here.
class MarchWorld {
 public:
  /// The most objects the list march takes (its masks of passed objects are 64 bits).
  static constexpr std::size_t kMostListed = 64;
  /// Validates the world (sol::validate) and prepares it. A Sol world of
  /// more than `listed` objects (sol::kListedObjects, the kernel's too;
  /// at most kMostListed) is marched through its tree of bounds: a larger
  /// `listed` is for comparing the two marches on one world.
  explicit MarchWorld(const World& world, std::size_t listed = kListedObjects);

  const World& world() const { return m_world; }
  const MarchFeatures& features() const { return m_features; }
  /// The quotient's lattice (World::lattice; none in Sol).
  const std::optional<Lattice>& lattice() const { return m_lattice; }
  /// Sol: the objects in world coordinates, one per scene object; the
  /// quotient: their images around D in world coordinates.
  const std::vector<MarchObject>& objects() const { return m_objects; }
  /// Sol: the objects relative to `origin` (left-translated by origin⁻¹),
  /// what a ray from `origin` marches through.
  std::vector<MarchObject> seen_from(const glm::dvec3& origin) const;
  /// Sol worlds of more than the listed objects (the constructor's
  /// `listed`): the tree of bounds over objects() (item k is
  /// objects()[k]); null otherwise.
  const BoundsTree* tree() const { return m_tree.get(); }
  /// The quotient: the distance field of objects() over D (null in Sol).
  const QuotientField* field() const { return m_field.get(); }
  /// The quotient: the longest march step (sol::quotient_max_step; 0 in Sol).
  double max_step() const { return m_max_step; }
  /// The quotient: each light's images (sol::quotient_light_images; empty
  /// for all but exact point lights, and in Sol).
  const std::vector<std::vector<glm::dvec3>>& light_images() const { return m_light_images; }

 private:
  World m_world;
  MarchFeatures m_features;
  std::optional<Lattice> m_lattice;
  std::vector<MarchObject> m_objects;
  std::shared_ptr<const BoundsTree> m_tree;
  std::shared_ptr<const QuotientField> m_field;
  double m_max_step = 0.0;
  std::vector<std::vector<glm::dvec3>> m_light_images;
};

/// The glowing scene objects next-event estimation draws points of on a
/// path (both renderers; docs/lighting.md): in Sol every glowing exact
/// ball, box, ball drawn by its bound and tube about a coordinate axis
/// (a glowing plane is found by reflection), in a crowd (more than the
/// listed objects) the first kListedObjects of them in the scene's order
/// (the kernel holds that many; the others found by reflection), in a
/// quotient the glowing exact balls (each image around D a target; the
/// other kinds found by reflection). Their indices, ascending.
std::vector<std::size_t> glow_target_objects(const MarchWorld& prepared);

}  // namespace sol
