#include "sol/scene.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include <glm/geometric.hpp>

#include "field_error.hpp"
#include "objects_internal.hpp"
#include "spaces/space_io.hpp"
#include "sol/error.hpp"

namespace sol {
namespace detail {

void check_camera(const Camera& camera);                    // camera.cpp
void check_light(const Light& light, const std::string& at);  // light.cpp
void check_display(const Display& display);                 // display.cpp

// The checks behind validate(World), also run on the world of a scene file.
void check_world(const World& s) {
  if (s.objects.empty()) field_error("objects", "the scene has no objects");
  if (s.objects.size() > kMaxObjects) {
    field_error("objects", "at most " + std::to_string(kMaxObjects) + " objects, got " + std::to_string(s.objects.size()));
  }
  if (s.quotient() != Quotient::None && s.objects.size() > kQuotientObjects) {
    field_error("objects", "a quotient world holds at most " + std::to_string(kQuotientObjects) + " objects, got " +
                               std::to_string(s.objects.size()) + " (Sol itself holds up to " + std::to_string(kMaxObjects) +
                               ")");
  }
  check_space(s.space);
  const std::optional<Lattice> lattice = s.lattice();
  for (std::size_t i = 0; i < s.objects.size(); ++i) {
    check_object(s.objects[i], "objects[" + std::to_string(i) + "]", lattice ? &*lattice : nullptr);
  }
  if (s.lights.size() > static_cast<std::size_t>(kMaxLights)) {
    field_error("lights", "at most " + std::to_string(kMaxLights) + " lights, got " + std::to_string(s.lights.size()));
  }
  for (std::size_t i = 0; i < s.lights.size(); ++i) {
    const std::string at = "lights[" + std::to_string(i) + "]";
    check_light(s.lights[i], at);
    // An exact light's images are found over a grid of D (sol::quotient_light_images): a bounded D.
    if (lattice && !lattice->compact() && s.lights[i].type == LightType::Point && s.lights[i].exact) {
      field_error(at + ".exact", at + ".exact: exact point lights are only in Sol and its compact quotients, not in a z loop "
                                      "or xy loops (set exact to false)");
    }
  }
  if (!(s.ambient >= 0.0 && s.ambient <= 1.0)) field_error("ambient", "ambient must be in [0, 1]");
  if (!unit_interval3(s.fog_color)) field_error("fog.color", "fog.color components must be in [0, 1]");
  if (!(s.fog_density >= 0.0) || !std::isfinite(s.fog_density)) {
    field_error("fog.density", "fog.density must be finite and >= 0");
  }
  if (!(s.fog_density <= 1e6)) field_error("fog.density", "fog.density must be at most 1e6 (fog within 1e-6)");
  if (!(s.max_distance > 0.0 && s.max_distance <= 1e4)) field_error("max_distance", "max_distance must be in (0, 10000]");
  if (!(s.max_steps >= 1 && s.max_steps <= 100000)) field_error("max_steps", "max_steps must be in [1, 100000]");
  if (!(s.hit_epsilon > 0.0 && s.hit_epsilon <= 0.1)) field_error("hit_epsilon", "hit_epsilon must be in (0, 0.1]");
  if (s.max_bounces && !(*s.max_bounces >= 0 && *s.max_bounces <= 64)) field_error("max_bounces", "max_bounces must be in [0, 64]");
}

}  // namespace detail

void validate(const World& world) {
  detail::validate_as("sol::validate(World)", [&] { detail::check_world(world); });
}

void validate(const Scene& scene) {
  detail::validate_as("sol::validate(Scene)", [&] {
    detail::check_camera(scene.camera);
    detail::check_world(scene);
    if (!(scene.samples >= 1 && scene.samples <= 4096)) detail::field_error("samples", "samples must be in [1, 4096]");
    detail::check_display(scene.display);
  });
}

bool uses_exact_lights(const World& world) {
  return std::any_of(world.lights.begin(), world.lights.end(),
                     [](const Light& l) { return l.type == LightType::Point && l.exact; });
}

bool uses_exact(const World& world) {
  return std::any_of(world.objects.begin(), world.objects.end(),
                     [](const SceneObject& o) { return is_exact_ball(o.shape); }) ||
         uses_exact_lights(world);
}

void set_space(World& world, const Space& space) {
  World next = world;
  next.space = space;
  const Lattice before = world.lattice().value_or(Lattice::default_axes());
  const Lattice after = next.lattice().value_or(Lattice::default_axes());  // throws for a bad monodromy
  for (SceneObject& o : next.objects) {
    if (Tube* t = std::get_if<Tube>(&o.shape)) {
      const std::optional<TubeAxis> axis = tube_axis_of(t->direction, before);
      if (axis == TubeAxis::Gamma1 || axis == TubeAxis::Gamma2) t->direction = tube_axis_direction(*axis, after);
    }
  }
  world = std::move(next);
}

std::vector<std::string> preset_names() {
  return {"plane",          "sandwich",     "sheets",         "lattice-balls",  "lattice-pillars", "lattice-boxes",
          "trace4-balls",   "trace4-pillars", "halfturn-balls", "spheres"};
}

Scene preset_scene(std::string_view name) {
  Scene s;
  if (name == "plane") {
    // The paper's "rolled into a tube" view: z = 0 seen from above.
    s.camera = {{0.0, 0.0, 1.5}, {0.0, 0.0, -1.0}, {0.0, 1.0, 0.0}, 90.0};
    s.objects = {{PlaneZ{0.0}, {0.95, 0.75, 0.3}, Pattern::Circles}};
  } else if (name == "sandwich") {
    // Looking along x + y: rays tilted up reach z = 1, tilted down z = -1
    // (straight along x every ray bends down, along y up).
    s.camera = {{0.0, 0.0, 0.0}, {1.0, 1.0, 0.0}, {0.0, 0.0, 1.0}, 90.0};
    s.objects = {{PlaneZ{1.0}, {0.35, 0.6, 0.95}, Pattern::Circles}, {PlaneZ{-1.0}, {0.95, 0.55, 0.3}, Pattern::Circles}};
    s.fog_density = 1.0 / 20.0;
  } else if (name == "sheets") {
    s.camera = {{1.0, 1.5, 0.2}, glm::normalize(glm::dvec3(-1.0, -1.2, -0.1)), {0.0, 0.0, 1.0}, 75.0};
    s.objects = {{PlaneX{0.0}, {0.9, 0.4, 0.35}, Pattern::Checker}, {PlaneY{0.0}, {0.35, 0.8, 0.45}, Pattern::Checker}};
    s.fog_density = 1.0 / 25.0;
  } else if (name == "lattice-balls") {
    // One ball at the base point of M = Γ\Sol: in the cover, a ball at every
    // point of Γ·o. Looking along z from inside the domain.
    s.space = GoldenSpace{};
    s.camera = {{0.9, 0.3, 0.45}, {0.0, 0.0, -1.0}, {0.0, 1.0, 0.0}, 90.0};
    s.objects = {{Ball{{0.0, 0.0, 0.0}, 0.25}, {0.9, 0.55, 0.3}}};
    s.fog_density = 1.0 / 12.0;
    s.max_distance = 12.0;
    s.max_steps = 400;
  } else if (name == "lattice-pillars") {
    // Tubes along the closed curves of γ1, γ2 and γ3 through the base point
    // of M: in the cover they run along the edges of the fundamental domains
    // and stake them out. Looking along x = y from the middle of the domain.
    s.space = GoldenSpace{};
    s.camera = {{1.3, 0.3, 0.48}, {1.0, 1.0, 0.0}, {0.0, 0.0, 1.0}, 90.0};
    for (const auto& [axis, color] : {std::pair{TubeAxis::Gamma1, glm::dvec3(0.9, 0.35, 0.3)},
                                      std::pair{TubeAxis::Gamma2, glm::dvec3(0.35, 0.8, 0.4)},
                                      std::pair{TubeAxis::Z, glm::dvec3(0.35, 0.5, 0.95)}}) {
      s.objects.push_back({make_tube(axis, {0.0, 0.0, 0.0}, 0.06, Lattice::golden()), color});
    }
    s.fog_density = 1.0 / 5.0;
    s.max_distance = 10.0;
    s.max_steps = 400;
  } else if (name == "lattice-boxes") {
    // A cube at the base point of M: in the cover, a cube at every point of
    // Γ·o, the cube lattices other Sol renderers show, here one box.
    // Looking along x + y, a little down, from inside the domain.
    s.space = GoldenSpace{};
    s.camera = {{0.9, 0.3, 0.45}, {1.0, 0.8, -0.3}, {0.0, 0.0, 1.0}, 90.0};
    s.objects = {{Box{{0.0, 0.0, 0.0}, {0.15, 0.15, 0.15}}, {0.35, 0.65, 0.9}, Pattern::Checker}};
    s.fog_density = 1.0 / 10.0;
    s.max_distance = 12.0;
    s.max_steps = 400;
  } else if (name == "trace4-balls" || name == "trace4-pillars") {
    // Another manifold: the torus bundle of A = [[3, 1], [2, 1]] (trace 4,
    // λ = 2 + √3: γ3 stretches x by 3.73, where the golden lattice's
    // stretches by 2.62). Its balls at Γ·o, or its tubes along γ1, γ2, γ3,
    // seen from the middle of its fundamental domain as the golden presets.
    s.space = MonodromySpace{.monodromy = {3, 1, 2, 1}};
    const Lattice lattice = *s.lattice();
    const glm::dvec3 middle =
        0.5 * (lattice.generators()[0] + lattice.generators()[1]) + glm::dvec3(0.0, 0.0, 0.5 * lattice.height());
    if (name == "trace4-balls") {
      s.camera = {middle, {0.0, 0.0, -1.0}, {0.0, 1.0, 0.0}, 90.0};
      s.objects = {{Ball{{0.0, 0.0, 0.0}, 0.3}, {0.9, 0.55, 0.3}}};
      s.fog_density = 1.0 / 12.0;
      s.max_distance = 12.0;
    } else {
      s.camera = {middle, {1.0, 1.0, 0.0}, {0.0, 0.0, 1.0}, 90.0};
      for (const auto& [axis, color] : {std::pair{TubeAxis::Gamma1, glm::dvec3(0.9, 0.35, 0.3)},
                                        std::pair{TubeAxis::Gamma2, glm::dvec3(0.35, 0.8, 0.4)},
                                        std::pair{TubeAxis::Z, glm::dvec3(0.35, 0.5, 0.95)}}) {
        s.objects.push_back({make_tube(axis, {0.0, 0.0, 0.0}, 0.06, lattice), color});
      }
      s.fog_density = 1.0 / 5.0;
      s.max_distance = 10.0;
    }
    s.max_steps = 400;
  } else if (name == "halfturn-balls") {
    // The torus bundle of [[-2, -1], [-1, -1]] (trace -3): the golden
    // lattice's translations, but γ3 also turns the fibre by the half-turn
    // (x, y) -> (-x, -y). A ball at the base point (orange; its images are
    // the golden lattice's) and one off it (blue): in the layers an odd
    // power of γ3 away its copies sit turned about the vertical axes of the
    // lattice points. Seen as lattice-balls.
    s.space = MonodromySpace{.monodromy = {-2, -1, -1, -1}};
    s.camera = {{0.9, 0.3, 0.45}, {0.0, 0.0, -1.0}, {0.0, 1.0, 0.0}, 90.0};
    s.objects = {{Ball{{0.0, 0.0, 0.0}, 0.25}, {0.9, 0.55, 0.3}}, {Ball{{0.75, 0.05, 0.3}, 0.15}, {0.35, 0.6, 0.95}}};
    s.fog_density = 1.0 / 12.0;
    s.max_distance = 12.0;
    s.max_steps = 400;
  } else if (name == "spheres") {
    // True geodesic spheres (exact balls) of radii 0.3 to 0.6 on, above and
    // below z = 0, seen from the origin along x + y: above z = 0 they stretch
    // along y, below along x (where e^{∓z} makes that direction cheap). An
    // exact point light near the observer.
    s.camera = {{0.0, 0.0, 0.0}, {1.0, 1.0, 0.0}, {0.0, 0.0, 1.0}, 100.0};
    const struct {
      glm::dvec3 center;
      double radius;
      glm::dvec3 color;
    } balls[] = {{{2.0, 2.0, 0.0}, 0.6, {0.9, 0.55, 0.3}},
                 {{1.0, 1.0, 1.0}, 0.4, {0.35, 0.6, 0.95}},
                 {{1.0, 1.0, -1.0}, 0.4, {0.4, 0.85, 0.45}},
                 {{2.0, 0.2, 0.0}, 0.3, {0.9, 0.85, 0.4}},
                 {{0.2, 2.0, 0.0}, 0.3, {0.85, 0.4, 0.8}}};
    for (const auto& b : balls) s.objects.push_back({Ball{b.center, b.radius, true}, b.color, Pattern::Checker});
    Light point;
    point.type = LightType::Point;
    point.position = {0.3, 0.2, 0.4};
    point.intensity = 4.0;
    point.exact = true;
    s.lights = {point};
    s.ambient = 0.2;
    s.max_distance = 14.0;
  } else {
    std::string list;
    for (const std::string& n : preset_names()) list += (list.empty() ? "" : ", ") + n;
    throw InvalidArgument("unknown preset '" + std::string(name) + "' (presets: " + list + ")");
  }
  return s;
}

}  // namespace sol
