#include "sol/objects.hpp"
#include "sol/materials.h"
#include "sol/patterns.h"

#include <filesystem>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <type_traits>

#include "field_error.hpp"
#include "objects_internal.hpp"
#include "sol/lattice.hpp"

namespace sol {

// ---- Helpers of the kinds' geometry

namespace detail {

double least_solid_bound(Solid solid, const glm::dvec3& c, const glm::dvec2& heading, const Lattice& lattice) {
  const DomainExtent e = lattice.domain_extent(c.z);
  if (solid == Solid::VerticalTube && std::isfinite(e.beyond)) return 0.0;  // no |Δz| term: near at some height
  const glm::dvec3 g1 = lattice.generators()[0], g2 = lattice.generators()[1];
  const glm::dvec2 corners[4] = {{0.0, 0.0}, {g1.x, g1.y}, {g2.x, g2.y}, {g1.x + g2.x, g1.y + g2.y}};
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;  // h_y Δx - h_x Δy over P
  for (const glm::dvec2& k : corners) {
    const double v = heading.y * (k.x - c.x) - heading.x * (k.y - c.y);
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  const double least_across = !e.xy_bounded || (lo <= 0.0 && hi >= 0.0) ? 0.0 : std::min(std::abs(lo), std::abs(hi));
  const double gx = gap(c.x, e.xlo, e.xhi), gy = gap(c.y, e.ylo, e.yhi);
  const double hx = std::abs(heading.x), hy = std::abs(heading.y);
  double least = e.beyond;
  for (int i = 0; i < e.slabs; ++i) {
    const double z0 = e.zlo + (e.zhi - e.zlo) * i / e.slabs, z1 = e.zlo + (e.zhi - e.zlo) * (i + 1) / e.slabs;
    double b = 0.0;
    if (solid == Solid::HorizontalTube) {
      const double denominator = std::max(hx * std::exp(-z0) + hy * std::exp(z0), hx * std::exp(-z1) + hy * std::exp(z1));
      b = std::max(gap(c.z, z0, z1), std::asinh(least_across / denominator));
    } else {
      b = std::max(std::asinh(gx * std::exp(-z1)), std::asinh(gy * std::exp(z0)));
      if (solid == Solid::Ball) b = std::max(b, gap(c.z, z0, z1));
    }
    least = std::min(least, b);
  }
  return least;
}

}  // namespace detail

// ---- Visiting shapes -------------------------------------------------------

std::string_view kind_name(const Shape& shape) {
  return std::visit(
      [](const auto& k) -> std::string_view {
        if constexpr (requires { k.name(); }) {
          return k.name();  // a composite: its operation
        } else {
          return std::decay_t<decltype(k)>::kName;
        }
      },
      shape);
}

double shape_distance(const Shape& shape, const glm::dvec3& q) {
  return std::visit([&](const auto& k) { return k.distance(q); }, shape);
}

double shape_clearance(const Shape& shape, const glm::dvec3& q, const glm::dvec3& u) {
  return shape_clearances(shape, q, u).ahead;
}

Clearances shape_clearances(const Shape& shape, const glm::dvec3& q, const glm::dvec3& u) {
  return std::visit(
      [&](const auto& k) {
        if constexpr (requires { k.clearances(q, u); }) {
          return k.clearances(q, u);  // a composite: its parts'
        } else {
          return clearances(k.clearance_terms(q, u));
        }
      },
      shape);
}

InsideClearances shape_inside_clearances(const Shape& shape, const glm::dvec3& q, const glm::dvec3& u) {
  return std::visit(
      [&](const auto& k) {
        if constexpr (requires { k.inside_terms(q, u); }) {
          return inside_clearances(k.inside_terms(q, u));
        } else if constexpr (requires { k.inside_clearances(q, u); }) {
          return k.inside_clearances(q, u);  // a composite: its parts'
        } else {
          const double d = -k.distance(q);
          return InsideClearances{d, d, 0.0};
        }
      },
      shape);
}

glm::dvec3 shape_normal(const Shape& shape, const glm::dvec3& q) {
  return std::visit([&](const auto& k) { return k.normal(q); }, shape);
}

Shape shape_seen_from(const Shape& shape, const glm::dvec3& p) {
  return std::visit([&](const auto& k) { return Shape(k.seen_from(p)); }, shape);
}

CoordinateBox shape_coordinate_box(const Shape& shape) {
  return std::visit([](const auto& k) { return k.coordinate_box(); }, shape);
}

bool is_exact_ball(const Shape& shape) {
  const Ball* b = std::get_if<Ball>(&shape);
  return b && b->exact;
}

bool is_solid(const Shape& shape) {
  return std::visit([](const auto& k) { return std::decay_t<decltype(k)>::kSolid; }, shape);
}

KernelShape kernel_shape(const Shape& shape) {
  return std::visit([](const auto& k) { return k.kernel_shape(); }, shape);
}

glm::dvec2 shape_pattern_uv(const Shape& shape, const glm::dvec3& q, const glm::dvec3& world) {
  return std::visit(
      [&](const auto& k) {
        using Kind = std::decay_t<decltype(k)>;
        if constexpr (Kind::kSolid) {
          return k.pattern_uv(q);
        } else {
          return k.pattern_uv(world);
        }
      },
      shape);
}

// ---- Patterns --------------------------------------------------------------

std::string_view to_string(Material material) {
#define SOL_MATERIAL_NAME(Enum, code_name, code, prefix, name) \
  if (material == Material::Enum) return name;
  SOL_MATERIALS(SOL_MATERIAL_NAME)
#undef SOL_MATERIAL_NAME
  return "?";
}

std::span<const Material> materials() {
#define SOL_MATERIAL_ITEM(Enum, code_name, code, prefix, name) Material::Enum,
  static constexpr Material all[] = {SOL_MATERIALS(SOL_MATERIAL_ITEM)};
#undef SOL_MATERIAL_ITEM
  return all;
}

glm::dvec4 material_params(const SceneObject& object) {
  const double x = object.material == Material::Glossy ? object.roughness
                   : object.material == Material::Glass ? object.ior
                                                        : object.mirror;
  return {x, 0.0, 0.0, 0.0};
}

kernel::SolLobes material_lobes(const SceneObject& object, const glm::dvec3& albedo) {
  return kernel::sol_material_lobes(static_cast<int>(object.material), albedo, material_params(object));
}

bool material_reflects(const SceneObject& object) {
  const glm::dvec3 specular = material_lobes(object, glm::dvec3(1.0)).specular;
  return specular.x > 0.0 || specular.y > 0.0 || specular.z > 0.0;
}

std::string_view to_string(Pattern p) {
  switch (p) {
    case Pattern::None:
      return "none";
    case Pattern::Circles:
      return "circles";
    case Pattern::Checker:
      return "checker";
  }
  return "?";
}

int pattern_code(Pattern pattern) {
  switch (pattern) {
    case Pattern::None:
      return kernel::kPatternNone;
    case Pattern::Circles:
      return kernel::kPatternCircles;
    case Pattern::Checker:
      return kernel::kPatternChecker;
  }
  return kernel::kPatternNone;
}

double pattern_factor(Pattern pattern, double u, double v) {
  return kernel::sol_pattern_factor(pattern_code(pattern), u, v);
}

// ---- Checks and scene-file keys, kind by kind -----------------------------

namespace detail {

void check_radius(double radius, const std::string& at, const Lattice* quotient) {
  if (!(radius > 0.0) || !std::isfinite(radius)) field_error(at + ".radius", at + ".radius must be finite and > 0");
  if (quotient && radius > kMaxQuotientRadius) {
    field_error(at + ".radius",
                at + ".radius must be <= 0.45 in the quotient (the listing of the objects' images around the domain assumes it)");
  }
}

json to_json(const glm::dvec3& v) { return json::array({v.x, v.y, v.z}); }

namespace {

// The kind named `name`, default-constructed; nullopt if there is none.
template <std::size_t I = 0>
std::optional<Shape> shape_named(std::string_view name) {
  if constexpr (I < std::variant_size_v<Shape>) {
    using Kind = std::variant_alternative_t<I, Shape>;
    if constexpr (std::is_same_v<Kind, Composite>) {
      if (const std::optional<CompositeOp> op = composite_op_named(name)) {
        Composite composite;
        composite.op = *op;
        return Shape(composite);
      }
    } else if (Kind::kName == name) {
      return Shape(Kind{});
    }
    return shape_named<I + 1>(name);
  } else {
    return std::nullopt;
  }
}

template <std::size_t... I>
std::string kind_names(std::index_sequence<I...>) {
  std::string list;
  const auto name = [](auto kind) {
    if constexpr (requires { kind.name(); }) {
      return std::string("union, intersection, difference");
    } else {
      return std::string(decltype(kind)::kName);
    }
  };
  ((list += std::string(I == 0 ? "" : ", ") + name(std::variant_alternative_t<I, Shape>{})), ...);
  return list;
}

Pattern read_pattern(const json& value, const SceneFileReader& r, const std::string& path) {
  return r.choice<Pattern>(value, path,
                           {{to_string(Pattern::None), Pattern::None},
                            {to_string(Pattern::Circles), Pattern::Circles},
                            {to_string(Pattern::Checker), Pattern::Checker}});
}

}  // namespace

void check_object(const SceneObject& o, const std::string& at, const Lattice* quotient) {
  std::visit([&](const auto& kind) { check_kind(kind, at, quotient); }, o.shape);
  if (o.cutout && (is_solid(o.shape) || o.pattern == Pattern::None)) {
    field_error(at + ".cutout", at + ".cutout needs a plane with a pattern (circles or checker)");
  }
  if (!unit_interval3(o.color)) field_error(at + ".color", at + ".color components must be in [0, 1]");
  for (int c = 0; c < 3; ++c) {
    if (!(o.emission[c] >= 0.0 && o.emission[c] <= 1e6)) {
      field_error(at + ".emission", at + ".emission components must be in [0, 1e6] (emitted radiance, linear)");
    }
  }
  if (!(o.mirror >= 0.0 && o.mirror <= 1.0)) field_error(at + ".mirror", at + ".mirror must be in [0, 1]");
  if (o.mirror != 0.0 && o.material != Material::Diffuse) {
    field_error(at + ".mirror", at + ".mirror is the diffuse material's share of mirror reflection; material \"" +
                                    std::string(to_string(o.material)) + "\" takes none");
  }
  if (!(o.roughness >= 0.0 && o.roughness <= 1.0)) field_error(at + ".roughness", at + ".roughness must be in [0, 1]");
  if (o.roughness != 0.0 && o.material != Material::Glossy) {
    field_error(at + ".roughness", at + ".roughness is the glossy material's; material \"" +
                                       std::string(to_string(o.material)) + "\" takes none");
  }
  if (o.material == Material::Glass && !(o.ior >= 1.0 && o.ior <= 3.0)) {
    field_error(at + ".ior", at + ".ior must be in [1, 3]");
  }
  if (o.ior != 0.0 && o.material != Material::Glass) {
    field_error(at + ".ior", at + ".ior is the glass material's index of refraction; material \"" +
                                 std::string(to_string(o.material)) + "\" takes none");
  }
  if (o.material == Material::Glass && !is_solid(o.shape)) {
    field_error(at + ".material", at + ".material: glass is for solids (balls, boxes, tubes and their composites), light "
                                       "goes through it to its far wall");
  }
  if (!(o.glow_reach >= 0.0 && o.glow_reach <= 10.0)) field_error(at + ".glow_reach", at + ".glow_reach must be in [0, 10]");
  try {
    validate_texture_cells(o.texture_cells, at + ".texture_cells");
  } catch (const InvalidArgument& e) {
    field_error(at + ".texture_cells", e.what());
  }
  try {
    if (o.texture) validate_texture(*o.texture, at + ".texture");
  } catch (const InvalidArgument& e) {
    field_error(at + ".texture", e.what());
  }
  if (o.glow_reach > 0.0) {
    const Ball* b = std::get_if<Ball>(&o.shape);
    if (!b || !b->exact || o.emission == glm::dvec3(0.0)) {
      field_error(at + ".glow_reach", at + ".glow_reach needs a glowing exact ball (\"exact\": true, an emission)");
    }
    if (quotient) {
      field_error(at + ".glow_reach", at + ".glow_reach: in a quotient paths reach glowing balls by reflection alone");
    }
  }
}

namespace {

// A "texture" key: an image file's name, relative to the scene file's
// folder (or the working directory for a scene not read from a file),
// read through the program's reader (sol::set_texture_reader).
std::shared_ptr<const Texture> read_texture_key(const json& value, const SceneFileReader& r, const std::string& at) {
  if (!value.is_string() || value.get<std::string>().empty()) {
    r.fail(at, "'" + at + "' must be an image file's name, got " + SceneFileReader::json_text(value));
  }
  const std::string named = value.get<std::string>();
  std::filesystem::path path(named);
  std::error_code ec;
  const std::filesystem::path source(r.source());
  if (path.is_relative() && !r.source().empty() && std::filesystem::is_regular_file(source, ec)) {
    path = source.parent_path() / path;
  }
  try {
    // Named by its absolute path from here on (sol::to_json writes it so):
    // a scene written elsewhere, or rebuilt from its JSON, finds it again.
    return read_texture(path.string(), std::filesystem::absolute(path, ec).lexically_normal().string());
  } catch (const InvalidArgument& e) {
    r.fail(at, "'" + at + "': " + e.what());
  }
}

// The shape of the object (or part) at `at`: its "type" and its kind's keys.
Shape read_shape(const json& o, SceneObject& obj, const SceneFileReader& r, const std::string& at, const Lattice* quotient,
                 bool part) {
  if (!o.is_object()) r.fail(at, at + " must be an object");
  if (!o.contains("type")) r.fail(at, at + " needs a 'type'");
  const std::string type = SceneFileReader::text(o["type"]);
  std::optional<Shape> shape = shape_named(type);
  if (!shape) {
    r.fail(at + ".type", "'" + at + ".type' must be one of " +
                             kind_names(std::make_index_sequence<std::variant_size_v<Shape>>()) +
                             (part ? "" : " (or array: copies of an object)") + ", got " +
                             SceneFileReader::json_text(o["type"]));
  }
  std::visit([&](auto& kind) { read_kind(kind, obj, o, r, at, quotient); }, *shape);
  return *shape;
}

}  // namespace

Shape read_part(const json& o, const SceneFileReader& r, const std::string& at, const Lattice* quotient) {
  if (o.is_object()) {
    for (const char* key : {"color", "pattern", "material", "emission", "mirror", "glow_reach", "cutout", "texture", "texture_cells"}) {
      if (o.contains(key)) {
        r.fail(at + "." + key, std::string("'") + key + "' in " + at +
                                   ": a part takes its kind's keys alone; its appearance is the composite's");
      }
    }
  }
  SceneObject ignored;
  return read_shape(o, ignored, r, at, quotient, true);
}

json write_part(const Shape& part, const Lattice* quotient) {
  json j = std::visit([&](const auto& kind) { return write_kind(kind, SceneObject{}, quotient); }, part);
  j["type"] = std::string(kind_name(part));
  return j;
}

SceneObject read_object(const json& o, const SceneFileReader& r, const std::string& at, const Lattice* quotient) {
  SceneObject obj;
  obj.shape = read_shape(o, obj, r, at, quotient, false);
  if (o.contains("color")) obj.color = r.vec3(o["color"], at + ".color");
  if (o.contains("pattern")) obj.pattern = read_pattern(o["pattern"], r, at + ".pattern");
#define SOL_MATERIAL_OPTION(Enum, code_name, code, prefix, name) {name, Material::Enum},
  if (o.contains("material")) obj.material = r.choice<Material>(o["material"], at + ".material", {SOL_MATERIALS(SOL_MATERIAL_OPTION)});
#undef SOL_MATERIAL_OPTION
  if (o.contains("emission")) obj.emission = r.vec3(o["emission"], at + ".emission");
  if (o.contains("mirror")) obj.mirror = r.number(o["mirror"], at + ".mirror");
  if (obj.material == Material::Glossy) obj.roughness = SceneObject::kDefaultRoughness;
  if (o.contains("roughness")) obj.roughness = r.number(o["roughness"], at + ".roughness");
  if (obj.material == Material::Glass) obj.ior = SceneObject::kDefaultIor;
  if (o.contains("ior")) obj.ior = r.number(o["ior"], at + ".ior");
  if (o.contains("glow_reach")) obj.glow_reach = r.number(o["glow_reach"], at + ".glow_reach");
  if (o.contains("texture")) obj.texture = read_texture_key(o["texture"], r, at + ".texture");
  if (o.contains("texture_cells")) {
    const json& cells = o["texture_cells"];
    if (!cells.is_array() || cells.size() != 2) {
      r.fail(at + ".texture_cells", "'" + at + ".texture_cells' must be an array of 2 numbers (pattern cells along u and v), got " +
                                        SceneFileReader::json_text(cells));
    }
    obj.texture_cells = {r.number(cells[0], at + ".texture_cells[0]"), r.number(cells[1], at + ".texture_cells[1]")};
  }
  return obj;
}

json write_object(const SceneObject& o, const Lattice* quotient) {
  json j = std::visit([&](const auto& kind) { return write_kind(kind, o, quotient); }, o.shape);
  j["type"] = std::string(kind_name(o.shape));
  j["color"] = to_json(o.color);
  j["pattern"] = std::string(to_string(o.pattern));
  if (o.material != Material::Diffuse) j["material"] = std::string(to_string(o.material));
  if (o.emission != glm::dvec3(0.0)) j["emission"] = to_json(o.emission);
  if (o.mirror != 0.0) j["mirror"] = o.mirror;
  if (o.material == Material::Glossy) j["roughness"] = o.roughness;
  if (o.material == Material::Glass) j["ior"] = o.ior;
  if (o.glow_reach != 0.0) j["glow_reach"] = o.glow_reach;
  if (o.texture) j["texture"] = o.texture->file;
  if (o.texture_cells != glm::dvec2(1.0)) j["texture_cells"] = json::array({o.texture_cells.x, o.texture_cells.y});
  return j;
}

}  // namespace detail
}  // namespace sol
