// Scene files: the documented schema parses, every malformed or inconsistent
// input is rejected with a message naming the problem, presets are valid and
// to_json round-trips.
#include <algorithm>
#include <cmath>
#include <string>
#include <variant>
#include <vector>

#include <glm/geometric.hpp>

#include <gtest/gtest.h>
#include <sol/sol.hpp>

namespace {

// The example of the issue, verbatim.
const char* kMinimal = R"({"camera": {"position": [0, 0, 1.5], "forward": [0, 0, -1], "up": [0, 1, 0], "fov": 90},
  "objects": [{"type": "plane_z", "c": 0.0, "color": [0.9, 0.8, 0.3], "pattern": "circles"}],
  "max_distance": 30, "max_steps": 200})";

TEST(Scene, ParsesTheDocumentedExample) {
  const sol::Scene s = sol::parse_scene(kMinimal);
  EXPECT_EQ(s.camera.position, glm::dvec3(0, 0, 1.5));
  EXPECT_EQ(s.camera.forward, glm::dvec3(0, 0, -1));
  EXPECT_EQ(s.camera.fov, 90.0);
  ASSERT_EQ(s.objects.size(), 1u);
  EXPECT_TRUE(std::holds_alternative<sol::PlaneZ>(s.objects[0].shape));
  EXPECT_EQ(s.objects[0].pattern, sol::Pattern::Circles);
  EXPECT_EQ(s.objects[0].color, glm::dvec3(0.9, 0.8, 0.3));
  EXPECT_EQ(s.max_distance, 30.0);
  EXPECT_EQ(s.max_steps, 200);
}

// Each bad input must throw InvalidArgument whose message contains the given words.
void expect_rejected(const std::string& json, const std::string& words) {
  try {
    (void)sol::parse_scene(json, "bad.json");
    ADD_FAILURE() << "accepted: " << json;
  } catch (const sol::InvalidArgument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("bad.json"), std::string::npos) << what;  // names the source
    EXPECT_NE(what.find(words), std::string::npos) << "message '" << what << "' lacks '" << words << "'";
  }
}

TEST(Scene, RejectsMalformedAndInconsistentInput) {
  const std::string objects = R"("objects": [{"type": "plane_z"}])";
  expect_rejected("{", "malformed JSON");
  expect_rejected("[1, 2]", "JSON object");
  expect_rejected("{}", "'objects'");
  expect_rejected(R"({"objects": []})", "no objects");
  expect_rejected(R"({"objects": [{"type": "sphere"}]})", "plane_x, plane_y, plane_z");
  expect_rejected(R"({"objects": [{"c": 1}]})", "needs a 'type'");
  expect_rejected(R"({"objects": [{"type": "plane_z", "colour": [1, 1, 1]}]})", "unknown key 'colour'");
  expect_rejected(R"({"objects": [{"type": "plane_z", "color": [1, 1]}]})", "array of 3 numbers");
  expect_rejected(R"({"objects": [{"type": "plane_z", "color": [2, 0, 0]}]})", "color");
  expect_rejected(R"({"objects": [{"type": "plane_z", "c": "nan"}]})", "must be a number");
  expect_rejected(R"({"objects": [{"type": "plane_z", "pattern": "dots"}]})", "none, circles or checker");
  expect_rejected(R"({"camera": {"forward": [0, 0, 0]}, )" + objects + "}", "camera.forward");
  expect_rejected(R"({"camera": {"forward": [0, 0, 2], "up": [0, 0, -1]}, )" + objects + "}", "parallel");
  expect_rejected(R"({"camera": {"fov": 180}, )" + objects + "}", "fov");
  expect_rejected(R"({"camera": {"zoom": 2}, )" + objects + "}", "unknown key 'zoom'");
  expect_rejected(R"({"camera": {"frustum": [1, -1, -1, 1]}, )" + objects + "}", "camera.frustum must have left < right");
  expect_rejected(R"({"camera": {"frustum": [-1, 1, -1]}, )" + objects + "}", "'camera.frustum' must be an array of 4");
  expect_rejected(R"({"camera": {"frustum": [-1, 1, -1, 1e9]}, )" + objects + "}", "within [-1000, 1000]");
  expect_rejected(R"({"max_steps": 2.5, )" + objects + "}", "integer");
  expect_rejected(R"({"max_steps": 0, )" + objects + "}", "max_steps");
  expect_rejected(R"({"max_distance": -1, )" + objects + "}", "max_distance");
  expect_rejected(R"({"max_distance": 1e999, )" + objects + "}", "1e999");
  expect_rejected(R"({"frobnicate": 1, )" + objects + "}", "unknown key 'frobnicate'");
  expect_rejected(R"({"objects": [{"type": "ball", "center": [0, 0, 0]}]})", "needs a 'radius'");
  expect_rejected(R"({"lights": [{"type": "spot"}], )" + objects + "}", "directional or point");
  expect_rejected(R"({"objects": [{"type": "plane_z", "cutout": true}]})", "cutout needs a plane with a pattern");
  expect_rejected(R"({"quotient": "torus", )" + objects + "}",
                  "'quotient' must be none, golden, {\"monodromy\": [[a, b], [c, d]]}, {\"z_loop\": h} or {\"xy_loops\": [[x1, y1], [x2, y2]]}, got \"torus\"");
  expect_rejected(R"({"quotient": 7, )" + objects + "}", "'quotient' must be none, golden, {\"monodromy\"");
  expect_rejected(R"({"camera": {"projection": ["fisheye"]}, )" + objects + "}",
                  "'camera.projection' must be perspective, equirectangular or fisheye, got [\"fisheye\"]");
  expect_rejected(R"({"objects": [{"type": "tube", "axis": "w", "through": [0, 0, 0], "radius": 1}]})",
                  "'objects[0].axis' must be x, y, z, gamma1, gamma2 or gamma3, got \"w\"");
  expect_rejected(R"({"objects": [{"type": "tube", "axis": 2, "through": [0, 0, 0], "radius": 1}]})",
                  "'objects[0].axis' must be x, y, z, gamma1, gamma2 or gamma3, got 2");
  expect_rejected(R"({"objects": [{"type": "tube", "axis": "x", "radius": 1}]})", "needs 'through'");
  expect_rejected(R"({"quotient": "golden", "objects": [{"type": "plane_x"}]})", "not supported in the quotient");
  expect_rejected(R"({"objects": [{"type": "plane_z", "pattern": "circles", "cutout": 1}]})", "true or false");
  expect_rejected(R"({"lights": [{"type": "point"}], )" + objects + "}", "needs a 'position'");
  expect_rejected(R"({"lights": [{"type": "point", "position": [0, 0, 1], "intensity": -1}], )" + objects + "}",
                  "lights[0].intensity");
  expect_rejected(R"({"lights": [{"type": "directional", "direction": [0, 0, 0]}], )" + objects + "}",
                  "lights[0].direction");
  expect_rejected(R"({"fog": {"density": -0.1}, )" + objects + "}", "fog.density");
  expect_rejected(R"({"fog": {"colour": [0, 0, 0]}, )" + objects + "}", "unknown key 'colour'");
  expect_rejected(R"({"fog": {}, "fog_distance": 3, )" + objects + "}", "either 'fog' or 'fog_distance'");
  expect_rejected(R"({"objects": [{"type": "ball", "radius": 1}]})", "needs a 'center'");
  expect_rejected(R"({"objects": [{"type": "ball", "center": [0, 0, 0], "radius": -1}]})", "objects[0].radius");
  expect_rejected(R"({"objects": [{"type": "ball", "center": [0, 0], "radius": 1}]})", "objects[0].center");
  expect_rejected(R"({"objects": [{"type": "ball", "center": [0, 0, 0], "radius": 1, "c": 2}]})", "unknown key 'c'");
  expect_rejected(R"({"objects": [{"type": "ball", "center": [0, 0, 0], "radius": 1, "pattern": "stripes"}]})",
                  "'objects[0].pattern' must be none, circles or checker, got \"stripes\"");
  expect_rejected(R"({"objects": [{"type": "ball", "center": [0, 0, 0], "radius": 1, "cutout": true}]})",
                  "unknown key 'cutout'");
  // The quotient: only objects whose images under Γ stay finite near D.
  const std::string golden = R"({"quotient": "golden", "objects": [)";
  expect_rejected(golden + R"({"type": "tube", "axis": "x", "through": [0, 0, 0], "radius": 0.1}]})",
                  "objects[0].axis: tubes along x or y do not close up in the quotient");
  expect_rejected(golden + R"({"type": "tube", "axis": "z", "through": [0.5, 0, 0], "radius": 0.1}]})",
                  "objects[0].through: a tube along z in the quotient must pass through a point (x, y) of the lattice");
  expect_rejected(golden + R"({"type": "ball", "center": [0, 0, 0], "radius": 0.5}]})",
                  "objects[0].radius must be <= 0.45 in the quotient");
  expect_rejected(golden + R"({"type": "plane_y", "c": 0}]})", "objects[0].type: planes x, y = c are not supported");
}

TEST(Scene, CameraFrustumRoundTrips) {
  const sol::Scene s = sol::parse_scene(R"({"camera": {"frustum": [-0.9, 0.7, -0.8, 0.6]}, "objects": [{"type": "plane_z"}]})");
  ASSERT_TRUE(s.camera.frustum.has_value());
  EXPECT_EQ(s.camera.frustum->left, -0.9);
  EXPECT_EQ(s.camera.frustum->up, 0.6);
  const sol::Scene back = sol::parse_scene(sol::to_json(s));
  ASSERT_TRUE(back.camera.frustum.has_value());
  EXPECT_EQ(back.camera.frustum->right, 0.7);
  EXPECT_EQ(back.camera.frustum->down, -0.8);
  EXPECT_FALSE(sol::parse_scene(sol::to_json(sol::preset_scene("plane"))).camera.frustum.has_value());
}

TEST(Scene, SamplesRoundTripAndAreChecked) {
  const sol::Scene s = sol::parse_scene(R"({"objects": [{"type": "plane_z"}], "samples": 16})");
  EXPECT_EQ(s.samples, 16);
  EXPECT_EQ(sol::parse_scene(sol::to_json(s)).samples, 16);
  EXPECT_EQ(sol::parse_scene(R"({"objects": [{"type": "plane_z"}]})").samples, 1);
  for (const char* bad : {R"({"objects": [{"type": "plane_z"}], "samples": 0})",
                          R"({"objects": [{"type": "plane_z"}], "samples": 4097})",
                          R"({"objects": [{"type": "plane_z"}], "samples": 2.5})"}) {
    try {
      sol::parse_scene(bad);
      ADD_FAILURE() << bad;
    } catch (const sol::InvalidArgument& e) {
      EXPECT_NE(std::string(e.what()).find("samples"), std::string::npos) << e.what();
    }
  }
  sol::Scene v = s;
  v.samples = 0;
  EXPECT_THROW(sol::validate(v), sol::InvalidArgument);
}

TEST(Scene, ExposureAndToneRoundTripAndAreChecked) {
  const sol::Scene s = sol::parse_scene(R"({"objects": [{"type": "plane_z"}], "exposure": -1.5, "tone": "aces"})");
  EXPECT_EQ(s.display.exposure, -1.5);
  EXPECT_EQ(s.display.tone, sol::Tone::Aces);
  EXPECT_EQ(sol::parse_scene(sol::to_json(s)).display, s.display);
  const sol::Scene plain = sol::parse_scene(R"({"objects": [{"type": "plane_z"}]})");
  EXPECT_EQ(plain.display, sol::Display{});
  EXPECT_EQ(sol::to_json(plain).find("exposure"), std::string::npos);  // the defaults are not written
  const struct {
    const char* text;
    const char* says;
  } bad[] = {{R"({"objects": [{"type": "plane_z"}], "exposure": 21})", "exposure must be finite and within ±20 stops"},
             {R"({"objects": [{"type": "plane_z"}], "exposure": "1"})", "exposure"},
             {R"({"objects": [{"type": "plane_z"}], "tone": "filmic"})", "'tone' must be clamp or aces"}};
  for (const auto& [text, says] : bad) {
    try {
      sol::parse_scene(text);
      ADD_FAILURE() << text;
    } catch (const sol::InvalidArgument& e) {
      EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
    }
  }
  sol::Scene v = s;
  v.display.exposure = std::nan("");
  EXPECT_THROW(sol::validate(v), sol::InvalidArgument);
  EXPECT_THROW(sol::validate(v.display), sol::InvalidArgument);
  EXPECT_EQ(sol::tone_names(), "clamp, aces");
}

TEST(Scene, ProjectionsRoundTripAndAreChecked) {
  const sol::Scene s = sol::parse_scene(
      R"({"camera": {"projection": "fisheye", "fisheye_fov": 220}, "objects": [{"type": "plane_z"}]})");
  EXPECT_EQ(s.camera.projection, sol::Projection::Fisheye);
  EXPECT_EQ(s.camera.fisheye_fov, 220.0);
  const sol::Scene back = sol::parse_scene(sol::to_json(s));
  EXPECT_EQ(back.camera.projection, sol::Projection::Fisheye);
  EXPECT_EQ(back.camera.fisheye_fov, 220.0);
  EXPECT_EQ(sol::parse_scene(R"({"camera": {"projection": "equirectangular"}, "objects": [{"type": "plane_z"}]})").camera.projection,
            sol::Projection::Equirectangular);
  for (const auto& [text, field] : {std::pair{R"({"camera": {"projection": "cylinder"}, "objects": [{"type": "plane_z"}]})", "camera.projection"},
                                    std::pair{R"({"camera": {"projection": "fisheye", "fisheye_fov": 0}, "objects": [{"type": "plane_z"}]})", "camera.fisheye_fov"},
                                    std::pair{R"({"camera": {"projection": "fisheye", "frustum": [-1, 1, -1, 1]}, "objects": [{"type": "plane_z"}]})", "camera.frustum"}}) {
    try {
      sol::parse_scene(text);
      ADD_FAILURE() << text;
    } catch (const sol::InvalidArgument& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  }
}

TEST(Scene, TubeAxesAndPatternsOnSolids) {
  const sol::Scene s = sol::parse_scene(R"({"quotient": "golden", "objects": [
    {"type": "tube", "axis": "gamma1", "through": [0, 0, 0.2], "radius": 0.1, "pattern": "checker"},
    {"type": "tube", "axis": "gamma2", "through": [0.3, 0, 0], "radius": 0.1},
    {"type": "tube", "axis": "gamma3", "through": [1, 1.618033988749895, 5], "radius": 0.1},
    {"type": "ball", "center": [0, 0, 0], "radius": 0.2, "pattern": "circles"}]})");
  auto axis = [](const sol::SceneObject& o) { return std::get<sol::Tube>(o.shape).direction; };
  EXPECT_EQ(axis(s.objects[0]), sol::tube_axis_direction(sol::TubeAxis::Gamma1, sol::Lattice::golden()));
  EXPECT_EQ(s.objects[0].pattern, sol::Pattern::Checker);
  EXPECT_EQ(axis(s.objects[1]), sol::tube_axis_direction(sol::TubeAxis::Gamma2, sol::Lattice::golden()));
  EXPECT_EQ(axis(s.objects[2]), sol::tube_axis_direction(sol::TubeAxis::Z, sol::Lattice::golden()));  // gamma3's closed curve is the vertical line
  EXPECT_EQ(s.objects[3].pattern, sol::Pattern::Circles);
  // The axes are the lattice's directions: γ1 = (φ, -1, 0), γ2 = (1, φ, 0).
  const double phi = 0.5 * (1.0 + std::sqrt(5.0));
  const glm::dvec3 g1 = sol::tube_axis_direction(sol::TubeAxis::Gamma1, sol::Lattice::golden()), g2 = sol::tube_axis_direction(sol::TubeAxis::Gamma2, sol::Lattice::golden());
  EXPECT_NEAR(g1.x * -1.0 - g1.y * phi, 0.0, 1e-15);
  EXPECT_NEAR(g2.x * phi - g2.y * 1.0, 0.0, 1e-15);
  EXPECT_NEAR(glm::length(g1), 1.0, 1e-15);
  const sol::Scene back = sol::parse_scene(sol::to_json(s));
  for (std::size_t k = 0; k < s.objects.size(); ++k) {
    if (k < 3) {
      EXPECT_EQ(axis(back.objects[k]), axis(s.objects[k]));
    }
    EXPECT_EQ(back.objects[k].pattern, s.objects[k].pattern);
  }
}

// Tubes along any horizontal or vertical direction: an array for "axis"
// (normalised), written back as an array, and in the quotient only along
// γ1 or γ2 (their images close up).
TEST(Scene, TubeAxesAsDirections) {
  const sol::Scene s = sol::parse_scene(R"({"objects": [
    {"type": "tube", "axis": [1, 1, 0], "through": [0, 0, 0], "radius": 0.1},
    {"type": "tube", "axis": [0, 0, -2], "through": [0, 0, 0], "radius": 0.1}]})");
  const sol::Tube& slanted = std::get<sol::Tube>(s.objects[0].shape);
  EXPECT_NEAR(slanted.direction.x, std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(slanted.direction.y, std::sqrt(0.5), 1e-15);
  EXPECT_TRUE(std::get<sol::Tube>(s.objects[1].shape).vertical());
  const sol::Scene back = sol::parse_scene(sol::to_json(s));
  EXPECT_EQ(back.objects[0].shape, s.objects[0].shape);
  EXPECT_EQ(back.objects[1].shape, s.objects[1].shape);
  expect_rejected(R"({"objects": [{"type": "tube", "axis": [1, 0, 1], "through": [0, 0, 0], "radius": 1}]})",
                  "objects[0].axis must be a unit vertical or horizontal direction");
  expect_rejected(R"({"objects": [{"type": "tube", "axis": [0, 0, 0], "through": [0, 0, 0], "radius": 1}]})",
                  "objects[0].axis must be a unit vertical or horizontal direction");
  const std::string golden = R"({"quotient": "golden", "objects": [)";
  expect_rejected(golden + R"({"type": "tube", "axis": [1, 1, 0], "through": [0, 0, 0], "radius": 0.1}]})",
                  "objects[0].axis: a horizontal tube closes up in the quotient only along its lattice's gamma1 or gamma2");
  // γ1 = (φ, -1, 0) given backwards is still the closed curve of γ1.
  const sol::Scene along = sol::parse_scene(
      golden + R"({"type": "tube", "axis": [-1.618033988749895, 1, 0], "through": [0, 0, 0], "radius": 0.1}]})");
  const glm::dvec3 d = std::get<sol::Tube>(along.objects[0].shape).direction;
  EXPECT_NEAR(glm::length(glm::cross(d, sol::tube_axis_direction(sol::TubeAxis::Gamma1, sol::Lattice::golden()))), 0.0, 1e-15);
}

// "quotient": {"monodromy": A, "fibre_area": S}: the torus bundle of A. Its
// axes gamma1 and gamma2 are its own lattice's: for A = [[3, 1], [2, 1]]
// (λ = 2 + √3) the rows u with u A = λ u and u A = u / λ are (1 + √3, 1) and
// (-1, (1 + √3)/2) up to scale, so γ1 ∝ (1 + √3, -1) and γ2 ∝ (1, (1 + √3)/2).
TEST(Scene, QuotientOfAMonodromy) {
  const std::string text = R"({"quotient": {"monodromy": [[3, 1], [2, 1]]}, "objects": [
    {"type": "tube", "axis": "gamma1", "through": [0, 0, 0], "radius": 0.1},
    {"type": "tube", "axis": "gamma2", "through": [0, 0, 0.3], "radius": 0.1},
    {"type": "ball", "center": [0.2, 0.1, 0.4], "radius": 0.3}]})";
  const sol::Scene s = sol::parse_scene(text);
  EXPECT_EQ(s.quotient(), sol::Quotient::Monodromy);
  EXPECT_EQ(s.space, sol::Space(sol::MonodromySpace{{3, 1, 2, 1}, std::nullopt}));
  const double r3 = std::sqrt(3.0);
  const glm::dvec3 g1 = std::get<sol::Tube>(s.objects[0].shape).direction;
  const glm::dvec3 g2 = std::get<sol::Tube>(s.objects[1].shape).direction;
  EXPECT_NEAR(glm::length(glm::cross(g1, glm::normalize(glm::dvec3(1.0 + r3, -1.0, 0.0)))), 0.0, 1e-14);
  EXPECT_NEAR(glm::length(glm::cross(g2, glm::normalize(glm::dvec3(1.0, 0.5 * (1.0 + r3), 0.0)))), 0.0, 1e-14);
  EXPECT_NEAR(s.lattice()->height(), std::log(2.0 + r3), 1e-15);
  // Written back with the names and the matrix, and read back the same.
  const std::string json = sol::to_json(s);
  EXPECT_NE(json.find("\"gamma1\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"monodromy\""), std::string::npos) << json;
  const sol::Scene back = sol::parse_scene(json);
  EXPECT_EQ(back.quotient(), s.quotient());
  EXPECT_EQ(back.space, s.space);
  for (std::size_t k = 0; k < s.objects.size(); ++k) EXPECT_EQ(back.objects[k].shape, s.objects[k].shape);
  // A fibre area scales the fibre (and round-trips).
  const sol::Scene big = sol::parse_scene(R"({"quotient": {"monodromy": [[3, 1], [2, 1]], "fibre_area": 10},
    "objects": [{"type": "plane_z", "c": 0.2}]})");
  EXPECT_EQ(std::get<sol::MonodromySpace>(big.space).fibre_area, 10.0);
  EXPECT_NEAR(big.lattice()->fibre_area(), 10.0, 1e-12);
  EXPECT_EQ(sol::parse_scene(sol::to_json(big)).space, big.space);
  // [[2, 1], [1, 1]] without an area is the golden lattice itself.
  const sol::Scene golden = sol::parse_scene(R"({"quotient": {"monodromy": [[2, 1], [1, 1]]}, "objects": [
    {"type": "tube", "axis": "gamma1", "through": [0, 0, 0], "radius": 0.1}]})");
  EXPECT_EQ(golden.lattice()->generators(), sol::Lattice::golden().generators());
  EXPECT_EQ(std::get<sol::Tube>(golden.objects[0].shape).direction, sol::tube_axis_direction(sol::TubeAxis::Gamma1, sol::Lattice::golden()));

  // Refusals name the field and the reason.
  const std::string objects = R"("objects": [{"type": "plane_z"}])";
  auto with = [&](const std::string& quotient) { return R"({"quotient": )" + quotient + ", " + objects + "}"; };
  expect_rejected(with(R"({"monodromy": [[2, 1], [1, 2]]})"), "quotient.monodromy: ");
  expect_rejected(with(R"({"monodromy": [[2, 1], [1, 2]]})"), "is not in SL(2, Z): its determinant is 3");
  expect_rejected(with(R"({"monodromy": [[1, 1], [0, 1]]})"), "is not hyperbolic: its trace is 2");
  expect_rejected(with(R"({"monodromy": [[0, -1], [1, 0]]})"), "is not hyperbolic: its trace is 0");
  // A negative trace is a lattice whose γ3 turns the fibre.
  EXPECT_TRUE(sol::parse_scene(with(R"({"monodromy": [[-2, -1], [-1, -1]]})")).lattice()->turns());
  expect_rejected(with(R"({"monodromy": [[3, 1], [2, 1]], "fibre_area": -1})"), "quotient.fibre_area: ");
  expect_rejected(with(R"({"monodromy": [[3, 1], [2, 1]], "fibre_area": 0})"), "fibre area must be in [0.01, 10000]");
  expect_rejected(with(R"({"monodromy": [[3, 1], [2, 1]], "fibre_area": 1e300})"), "quotient.fibre_area: ");
  expect_rejected(with(R"({"monodromy": [3, 1, 2, 1]})"), "'quotient.monodromy' must be a 2 x 2 integer matrix");
  expect_rejected(with(R"({"monodromy": [[3, 1], [2]]})"), "'quotient.monodromy' must be a 2 x 2 integer matrix");
  expect_rejected(with(R"({"monodromy": [[3, 1.5], [2, 1]]})"), "'quotient.monodromy[0][1]' must be an integer");
  expect_rejected(with(R"({"monodromy": [[3, 1], [2, 1e12]]})"), "'quotient.monodromy[1][1]' must be an integer within");
  expect_rejected(with(R"({"monodromy": [[3, 1], [2, "1"]]})"), "quotient.monodromy[1][1]");
  expect_rejected(with(R"({"matrix": [[3, 1], [2, 1]]})"), "'quotient' needs one of the keys 'monodromy', 'z_loop', 'xy_loops', got {\"matrix\"");
  expect_rejected(with(R"({"fibre_area": 2})"), "'quotient' needs one of the keys 'monodromy', 'z_loop', 'xy_loops'");
  // The golden lattice's γ1 is no closed curve of another lattice.
  expect_rejected(R"({"quotient": {"monodromy": [[3, 1], [2, 1]]}, "objects": [
    {"type": "tube", "axis": [1.618033988749895, -1, 0], "through": [0, 0, 0], "radius": 0.1}]})",
                  "only along its lattice's gamma1 or gamma2");
  // validate() names the field too.
  sol::World world = s;
  world.space = sol::MonodromySpace{{4, 1, 1, 1}};
  try {
    sol::validate(world);
    ADD_FAILURE() << "accepted a matrix of determinant 3";
  } catch (const sol::InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("quotient.monodromy: "), std::string::npos) << e.what();
  }
}

// Every space of SOL_QUOTIENT_SPACES (and Sol): a world moved into it with
// its defaults validates, is written under its key and read back as the
// same space, with a lattice exactly where it is a quotient. A space added
// to the list is checked here without a line of its own.
TEST(Scene, EverySpaceOfTheListIsReadBack) {
  struct Listed {
    sol::Quotient value;
    std::string key;
  };
  std::vector<Listed> listed{{sol::Quotient::None, "none"}};
#define SOL_LISTED(type, value, key, form) listed.push_back({sol::Quotient::value, key});
  SOL_QUOTIENT_SPACES(SOL_LISTED)
#undef SOL_LISTED
  ASSERT_EQ(listed.size(), std::variant_size_v<sol::Space>);
  sol::Scene scene;
  sol::SceneObject plane;
  plane.shape = sol::PlaneZ{0.3};
  scene.objects = {plane};
  for (const Listed& l : listed) {
    SCOPED_TRACE(l.key);
    const sol::Space space = sol::default_space(l.value);
    EXPECT_EQ(sol::quotient_of(space), l.value);
    sol::set_space(scene, space);
    EXPECT_NO_THROW(sol::validate(scene));
    EXPECT_EQ(scene.lattice().has_value(), l.value != sol::Quotient::None);
    const std::string text = sol::to_json(scene);
    EXPECT_NE(text.find("\"" + l.key + "\""), std::string::npos) << text;
    const sol::Scene back = sol::parse_scene(text);
    EXPECT_EQ(back.space, space);
    EXPECT_TRUE(sol::same_space(back, scene));
    if (scene.lattice()) {
      EXPECT_EQ(back.lattice()->generators(), scene.lattice()->generators());
    }
  }
  // The defaults: the golden lattice twice (its own name, and its
  // monodromy without a fibre area), the unit loops.
  EXPECT_EQ(sol::lattice_of(sol::default_space(sol::Quotient::Monodromy))->generators(),
            sol::Lattice::golden().generators());
  EXPECT_EQ(sol::lattice_of(sol::default_space(sol::Quotient::ZLoop))->height(), 1.0);
}

// The non-compact quotients in scene files: {"z_loop": h} and {"xy_loops":
// [[x1, y1], [x2, y2]]}, written back as read; what each allows (balls,
// boxes, planes z = c; a z loop's tubes: horizontal ones and the z axis,
// xy loops': along γ1 or γ2) and the refusals, naming the field.
TEST(Scene, NonCompactQuotients) {
  const sol::Scene z = sol::parse_scene(R"({"quotient": {"z_loop": 1.5}, "objects": [
    {"type": "ball", "center": [3, -2, 7], "radius": 0.3},
    {"type": "box", "center": [0, 1, 0], "half_size": [0.1, 0.1, 0.1]},
    {"type": "plane_z", "c": -0.4},
    {"type": "tube", "axis": "z", "through": [0, 0, 5], "radius": 0.1},
    {"type": "tube", "axis": [0.6, 0.8, 0], "through": [1, 2, 0.3], "radius": 0.1}]})");
  EXPECT_EQ(z.quotient(), sol::Quotient::ZLoop);
  EXPECT_EQ(std::get<sol::ZLoopSpace>(z.space).height, 1.5);
  EXPECT_EQ(z.lattice()->generators()[2], glm::dvec3(0.0, 0.0, 1.5));
  const sol::Scene z_back = sol::parse_scene(sol::to_json(z));
  EXPECT_TRUE(sol::same_space(z_back, z));
  for (std::size_t k = 0; k < z.objects.size(); ++k) EXPECT_EQ(z_back.objects[k].shape, z.objects[k].shape);
  const sol::Scene xy = sol::parse_scene(R"({"quotient": {"xy_loops": [[2, 0], [0.5, 1.5]]}, "objects": [
    {"type": "ball", "center": [3, -2, 0.5], "radius": 0.3},
    {"type": "tube", "axis": "gamma1", "through": [0, 0, 0.2], "radius": 0.1},
    {"type": "tube", "axis": "x", "through": [0, 1, -0.2], "radius": 0.1},
    {"type": "tube", "axis": "gamma2", "through": [0, 0, 0.4], "radius": 0.1}]})");
  EXPECT_EQ(xy.quotient(), sol::Quotient::XYLoops);
  EXPECT_EQ(std::get<sol::XYLoopsSpace>(xy.space).loops[1], glm::dvec2(0.5, 1.5));
  EXPECT_NEAR(glm::length(glm::cross(std::get<sol::Tube>(xy.objects[3].shape).direction,
                                     glm::normalize(glm::dvec3(0.5, 1.5, 0.0)))), 0.0, 1e-15);
  const sol::Scene xy_back = sol::parse_scene(sol::to_json(xy));
  EXPECT_TRUE(sol::same_space(xy_back, xy));
  EXPECT_FALSE(sol::same_space(xy_back, z));

  const std::string plane = R"("objects": [{"type": "plane_z"}])";
  auto with = [&](const std::string& quotient, const std::string& objects) {
    return R"({"quotient": )" + quotient + ", " + objects + "}";
  };
  expect_rejected(with(R"({"z_loop": 0.5})", plane), "quotient.z_loop: ");
  expect_rejected(with(R"({"z_loop": 0.5})", plane), "must be in [1, 20]");
  expect_rejected(with(R"({"z_loop": "1"})", plane), "quotient.z_loop");
  expect_rejected(with(R"({"xy_loops": [[1, 2], [2, 4]]})", plane), "quotient.xy_loops: ");
  expect_rejected(with(R"({"xy_loops": [[1, 2], [2, 4]]})", plane), "(they are parallel)");
  expect_rejected(with(R"({"xy_loops": [1, 0, 0, 1]})", plane), "'quotient.xy_loops' must be two vectors");
  expect_rejected(with(R"({"xy_loops": [[1, 0], [0, "1"]]})", plane), "quotient.xy_loops[1][1]");
  expect_rejected(with(R"({"z_loop": 2, "xy_loops": [[1, 0], [0, 1]]})", plane), "not several");
  expect_rejected(with(R"({"z_loop": 2, "fibre_area": 3})", plane), "unknown key 'fibre_area' in quotient (a z loop's)");
  // What each allows.
  expect_rejected(with(R"({"z_loop": 2})", R"("objects": [{"type": "tube", "axis": "z", "through": [1, 0, 0], "radius": 0.1}])"),
                  "objects[0].through: a tube along z in a z loop must be the axis x = y = 0");
  expect_rejected(with(R"({"z_loop": 2})", R"("objects": [{"type": "plane_x", "c": 0}])"),
                  "objects[0].type: planes x, y = c are not supported in the quotient");
  expect_rejected(with(R"({"xy_loops": [[1, 0], [0, 1]]})",
                       R"("objects": [{"type": "tube", "axis": "z", "through": [0, 0, 0], "radius": 0.1}])"),
                  "objects[0].axis: a tube along z does not fit xy loops");
  expect_rejected(with(R"({"xy_loops": [[1, 0.5], [0, 1]]})",
                       R"("objects": [{"type": "tube", "axis": "x", "through": [0, 0, 0], "radius": 0.1}])"),
                  "objects[0].axis: tubes along x or y do not close up");
  expect_rejected(with(R"({"xy_loops": [[1, 0], [0, 1]]})", R"("objects": [{"type": "ball", "center": [0, 0, 0], "radius": 0.5}])"),
                  "objects[0].radius must be <= 0.45");
  expect_rejected(with(R"({"z_loop": 2})", R"("objects": [{"type": "plane_z"}],
                       "lights": [{"type": "point", "position": [0, 0, 0.5], "exact": true}])"),
                  "lights[0].exact: exact point lights are only in Sol and its compact quotients");
}

// set_space moves a world to another space: tubes along the lattice's γ1
// and γ2 follow the lattice, and back; a bad monodromy leaves it as it was.
TEST(Scene, SetSpaceCarriesTheClosedCurves) {
  const sol::Scene pillars = sol::preset_scene("lattice-pillars");
  sol::World world = pillars;
  sol::set_space(world, sol::MonodromySpace{{5, 2, 2, 1}, 6.0});
  const sol::Lattice lattice = *world.lattice();
  EXPECT_NEAR(lattice.fibre_area(), 6.0, 1e-12);
  EXPECT_EQ(std::get<sol::Tube>(world.objects[0].shape).direction, glm::normalize(lattice.generators()[0]));
  EXPECT_EQ(std::get<sol::Tube>(world.objects[1].shape).direction, glm::normalize(lattice.generators()[1]));
  EXPECT_EQ(std::get<sol::Tube>(world.objects[2].shape).direction, glm::dvec3(0, 0, 1));
  EXPECT_NO_THROW(sol::validate(world));
  const sol::World before = world;
  EXPECT_THROW(sol::set_space(world, sol::MonodromySpace{{1, 1, 0, 1}}), sol::InvalidArgument);
  EXPECT_EQ(to_json(sol::Scene{world}), to_json(sol::Scene{before}));
  sol::set_space(world, sol::GoldenSpace{});
  EXPECT_EQ(world.space, sol::Space(sol::GoldenSpace{}));
  for (std::size_t k = 0; k < world.objects.size(); ++k) EXPECT_EQ(world.objects[k].shape, pillars.objects[k].shape);
}

// validate() of a world, a camera and a scene name the field and say which check spoke.
TEST(Scene, ValidateNamesTheField) {
  sol::World world = sol::preset_scene("plane");
  world.lights[0].intensity = -1.0;
  try {
    sol::validate(world);
    ADD_FAILURE() << "accepted a negative intensity";
  } catch (const sol::InvalidArgument& e) {
    EXPECT_EQ(std::string(e.what()), "sol::validate(World): lights[0].intensity must be finite and >= 0");
  }
  sol::Camera camera;
  camera.fov = 0.0;
  try {
    sol::validate(camera);
    ADD_FAILURE() << "accepted fov 0";
  } catch (const sol::InvalidArgument& e) {
    EXPECT_EQ(std::string(e.what()), "sol::validate(Camera): camera.fov must be in (0, 180) degrees");
  }
  sol::Scene scene = sol::preset_scene("plane");
  scene.camera = camera;
  EXPECT_THROW(sol::validate(scene), sol::InvalidArgument);
  EXPECT_NO_THROW(sol::validate(static_cast<const sol::World&>(scene)));  // the world alone is fine
}

TEST(Scene, ErrorsSayWhereInTheFile) {
  // Each message names the field and the line and column its value starts on.
  const std::string text = "{\n  \"camera\": {\"fov\": 90},\n  \"objects\": [\n    {\"type\": \"plane_z\"},\n"
                           "    {\"type\": \"ball\", \"center\": [0, 0, 0],\n     \"radius\": -2}\n  ]\n}\n";
  expect_rejected(text, "objects[1].radius must be finite and > 0 (line 6, column 16)");
  expect_rejected("{\"objects\": [{\"type\": \"plane_z\",\n \"colour\": [1, 0, 0]}]}", "(line 2, column 12)");
  expect_rejected("{\"objects\": [{\"type\": \"plane_z\"}],\n\n \"max_steps\": 0}", "max_steps must be in [1, 100000] (line 3, column 15)");
  // A check of the whole scene (after parsing) finds the light's field, on line 3.
  expect_rejected("{\"objects\": [{\"type\": \"plane_z\"}],\n\"lights\": [{\"type\": \"point\", \"position\": [0, 0, 1],\n"
                  "  \"intensity\": -1}]}",
                  "lights[0].intensity must be finite and >= 0 (line 3, column 16)");
  // A key a ball lacks: the place of the ball.
  expect_rejected("{\"objects\": [\n  {\"type\": \"ball\", \"center\": [0, 0, 0]}]}", "needs a 'radius' (line 2, column 3)");
}

// The message for `text` (which must be rejected), "" if it was accepted.
std::string rejection(const std::string& text) {
  try {
    (void)sol::parse_scene(text, "bad.json");
  } catch (const sol::InvalidArgument& e) {
    return e.what();
  }
  return "";
}

TEST(Scene, HostileTextIsRefusedBriefly) {
  // Nesting 100000 deep (a parser recursing per level would overflow the
  // stack): refused at the level past kSceneFileMaxDepth = 32. The scene
  // object is level 1, the objects array 2, so the 31st '[' after it (column
  // 13 + 31) opens level 33.
  const std::string deep = "{\"objects\": " + std::string(100000, '[') + std::string(100000, ']') + "}";
  EXPECT_EQ(rejection(deep), "bad.json: nesting deeper than 32 levels of objects and arrays (line 1, column 44)");
  // Exactly 32 levels pass that check (and fail on the schema), and brackets
  // inside strings do not count.
  const std::string level32 = "{\"objects\": " + std::string(31, '[') + std::string(31, ']') + "}";
  EXPECT_EQ(rejection(level32).find("nesting"), std::string::npos) << rejection(level32);
  const std::string in_string = R"({"objects": [{"type": "plane_z", ")" + std::string(100, '[') + R"(": 1}]})";
  EXPECT_NE(rejection(in_string).find("unknown key '[[["), std::string::npos) << rejection(in_string);
  // A NUL byte, after the JSON value or inside a string: nothing is ignored.
  const std::string valid = R"({"objects": [{"type": "plane_z"}]})";
  EXPECT_NO_THROW((void)sol::parse_scene(valid));
  EXPECT_EQ(rejection(valid + std::string(1, '\0') + "garbage"), "bad.json: malformed JSON: a NUL byte (line 1, column 35)");
  EXPECT_NE(rejection(std::string(R"({"objects": [{"type": "plane_z)") + '\0' + R"("}]})").find("NUL byte"), std::string::npos);
  // Values and keys of megabytes are shown cut, with their length.
  const std::string long_key = rejection(R"({"objects": [], ")" + std::string(5000000, 'k') + R"(": 1})");
  EXPECT_NE(long_key.find("unknown key 'kkkk"), std::string::npos) << long_key.substr(0, 200);
  EXPECT_NE(long_key.find("... (5000000 bytes)"), std::string::npos) << long_key.substr(0, 200);
  EXPECT_LT(long_key.size(), 400u);
  const std::string long_value = rejection(R"({"objects": [{"type": ")" + std::string(5000000, 'b') + R"("}]})");
  EXPECT_NE(long_value.find("got \"bbbb"), std::string::npos) << long_value.substr(0, 200);
  EXPECT_LT(long_value.size(), 400u);
  std::string many = "1";
  for (int i = 0; i < 200000; ++i) many += ", 1";
  const std::string long_array = rejection(R"({"objects": [{"type": "plane_z", "color": [)" + many + R"(]}]})");
  EXPECT_NE(long_array.find("array of 3 numbers, got [1,1,1"), std::string::npos) << long_array.substr(0, 200);
  EXPECT_LT(long_array.size(), 400u);
  // The parser's own messages too (it quotes a number that overflows whole).
  const std::string long_number = rejection(R"({"objects": [{"type": "plane_z", "c": )" + std::string(1000000, '1') + "}]}");
  EXPECT_NE(long_number.find("malformed JSON"), std::string::npos) << long_number.substr(0, 200);
  EXPECT_LT(long_number.size(), 500u);
  // Bytes that are not UTF-8 (a UTF-16 byte-order mark, a Latin-1 é) are
  // named in the message as \xNN: it stays text (Python raised a
  // ValueError with an empty message where it could not decode it).
  EXPECT_NE(rejection("\xff\xfe").find("last read: '\\xFF'"), std::string::npos) << rejection("\xff\xfe");
  const std::string latin1 = rejection(R"({"objects": [{"type": "caf)" + std::string("\xe9") + R"("}]})");
  EXPECT_NE(latin1.find("\\xE9"), std::string::npos) << latin1;
  for (const std::string& message : {rejection("\xff\xfe"), latin1}) {
    for (unsigned char c : message) EXPECT_LT(c, 0x80) << message;  // ASCII here: the bytes escaped
  }
  // Cut at a character, not inside a UTF-8 sequence (é is two bytes).
  std::string accents;
  for (int i = 0; i < 100; ++i) accents += "\xc3\xa9";
  const std::string cut = rejection(R"({"objects": [{"type": "x)" + accents + R"("}]})");
  const std::size_t got = cut.find("got \"x");
  ASSERT_NE(got, std::string::npos) << cut;
  const std::string shown = cut.substr(got + 5, cut.find("...", got) - got - 5);
  EXPECT_EQ(shown.size() % 2, 1u) << shown;  // "x" and whole "é"s
}

TEST(Scene, RefusesWhatTheRenderersCannotRepresent) {
  // Heights beyond [-80, 80] (e^{±z} leaves float in the kernel; far beyond,
  // double in the flows and teleports), for every position, named by field.
  const std::string plane = R"({"type": "plane_z"})";
  expect_rejected(R"({"camera": {"position": [0, 0, 800]}, "objects": [)" + plane + "]}",
                  "camera.position must have its height z within [-80, 80]");
  expect_rejected(R"({"camera": {"position": [0, 0, -80.5]}, "objects": [)" + plane + "]}", "camera.position");
  expect_rejected(R"({"objects": [{"type": "ball", "center": [0, 0, 800], "radius": 0.3}], "quotient": "golden"})",
                  "objects[0].center must have its height z within [-80, 80]");
  expect_rejected(R"({"objects": [{"type": "tube", "through": [0, 0, -800], "axis": "x", "radius": 0.1}]})",
                  "objects[0].through must have its height z within [-80, 80]");
  expect_rejected(R"({"objects": [{"type": "plane_z", "c": 100}]})", "objects[0].c is a height: it must be within [-80, 80]");
  expect_rejected(R"({"objects": [)" + plane + R"(], "lights": [{"type": "point", "position": [0, 0, 710]}]})",
                  "lights[0].position must have its height z within [-80, 80]");
  EXPECT_NO_THROW((void)sol::parse_scene(R"({"camera": {"position": [1e15, -1e15, 80]}, "objects": [{"type": "plane_z", "c": -80}]})"));
  // Planes x, y = c may lie anywhere within 1e15.
  EXPECT_NO_THROW((void)sol::parse_scene(R"({"objects": [{"type": "plane_x", "c": 1e12}]})"));
  // Colours stay finite: intensities up to 1e9 (1e39 gave +Inf pixels).
  expect_rejected(R"({"objects": [)" + plane + R"(], "lights": [{"type": "point", "position": [0, 0, 1], "intensity": 1e39}]})",
                  "lights[0].intensity must be at most 1e9");
  // The right cause: a fog distance whose inverse overflows, directions
  // whose length overflows or underflows (not "parallel").
  expect_rejected(R"({"objects": [)" + plane + R"(], "fog_distance": 1e-320})", "fog_distance must be 0 (no fog) or at least 1e-6");
  expect_rejected(R"({"objects": [)" + plane + R"(], "fog": {"density": 1e300}})", "fog.density must be at most 1e6");
  expect_rejected(R"({"camera": {"forward": [1e308, 1e308, 0]}, "objects": [)" + plane + "]}",
                  "camera.forward must have components of at most 1e100");
  expect_rejected(R"({"camera": {"up": [0, 0, 1e-320]}, "objects": [)" + plane + "]}", "camera.up must have components");
  expect_rejected(R"({"objects": [)" + plane + R"(], "lights": [{"type": "directional", "direction": [1e200, 0, 0]}]})",
                  "lights[0].direction must have components");
}

TEST(Scene, LightsAndFog) {
  const sol::Scene s = sol::parse_scene(R"({"objects": [{"type": "plane_z"}],
    "lights": [{"type": "directional", "direction": [0, 0, 1], "color": [1, 0.5, 0.5], "intensity": 0.7},
               {"type": "point", "position": [1, 2, 3]}],
    "ambient": 0.2, "fog": {"color": [0.1, 0.2, 0.3], "density": 0.05}})");
  ASSERT_EQ(s.lights.size(), 2u);
  EXPECT_EQ(s.lights[0].type, sol::LightType::Directional);
  EXPECT_EQ(s.lights[0].intensity, 0.7);
  EXPECT_EQ(s.lights[1].type, sol::LightType::Point);
  EXPECT_EQ(s.lights[1].position, glm::dvec3(1, 2, 3));
  EXPECT_EQ(s.ambient, 0.2);
  EXPECT_EQ(s.fog_density, 0.05);
  // The first schema's keys still read: fog_distance d is density 1/d.
  EXPECT_EQ(sol::parse_scene(R"({"objects": [{"type": "plane_z"}], "fog_distance": 4})").fog_density, 0.25);
}

// Arrays: {"type": "array", "of": o, "count": [nx, ny, nz], "step": s} is
// the nx·ny·nz left translates g·o, g = (i sx, j sy, k sz). Checked by the
// isometry itself: the distance bound of copy (i, j, k) at g·q is the
// original's at q (every kind's bound is left-invariant), with g·q written
// out here from the group law (x, y, z)·(x', y', z') = (x + e^z x',
// y + e^{-z} y', z + z'), and a ball's centre moved to g·c.
glm::dvec3 times(const glm::dvec3& g, const glm::dvec3& q) {
  return {g.x + std::exp(g.z) * q.x, g.y + std::exp(-g.z) * q.y, g.z + q.z};
}

TEST(Scene, ArraysAreLeftTranslatesOfTheirObject) {
  const glm::dvec3 step{0.7, -0.4, 0.3};
  const std::string kinds[] = {
      R"({"type": "ball", "center": [0.2, -0.1, 0.4], "radius": 0.3})",
      R"({"type": "ball", "center": [0.2, -0.1, 0.4], "radius": 0.3, "exact": true})",
      R"({"type": "box", "center": [-0.3, 0.2, 0.1], "half_size": [0.2, 0.1, 0.3]})",
      R"({"type": "tube", "axis": "x", "through": [0.1, 0.5, -0.2], "radius": 0.2})",
      R"({"type": "tube", "axis": "z", "through": [0.1, 0.5, -0.2], "radius": 0.2})",
      R"({"type": "tube", "axis": [1, 2, 0], "through": [0.1, 0.5, -0.2], "radius": 0.2})",
      R"({"type": "plane_x", "c": 0.6})",
      R"({"type": "plane_y", "c": -0.6})",
      R"({"type": "plane_z", "c": -0.5})"};
  const glm::dvec3 points[] = {{0.3, 0.2, -0.4}, {-1.2, 0.7, 0.9}, {0.05, -0.3, 0.35}, {2.0, 1.5, -1.1}};
  for (const std::string& kind : kinds) {
    const sol::Scene original = sol::parse_scene(R"({"objects": [)" + kind + "]}");
    const sol::Scene s = sol::parse_scene(R"({"objects": [{"type": "array", "count": [2, 3, 2], "step": [0.7, -0.4, 0.3],
      "of": )" + kind + "}]}");
    ASSERT_EQ(s.objects.size(), 12u) << kind;
    const sol::Shape& o = original.objects[0].shape;
    for (int k = 0, n = 0; k < 2; ++k) {
      for (int j = 0; j < 3; ++j) {
        for (int i = 0; i < 2; ++i, ++n) {  // i the fastest
          const glm::dvec3 g = glm::dvec3(i, j, k) * step;
          const sol::Shape& copy = s.objects[static_cast<std::size_t>(n)].shape;
          EXPECT_EQ(copy.index(), o.index()) << kind;
          for (const glm::dvec3& q : points) {
            const double d = sol::shape_distance(o, q);
            EXPECT_NEAR(sol::shape_distance(copy, times(g, q)), d, 1e-12 * std::max(1.0, std::abs(d)))
                << kind << " copy " << i << j << k;
          }
          if (const auto* ball = std::get_if<sol::Ball>(&copy)) {
            const glm::dvec3 c = times(g, std::get<sol::Ball>(o).center);
            EXPECT_NEAR(glm::length(ball->center - c), 0.0, 1e-14) << kind;
            EXPECT_EQ(ball->radius, 0.3);
          }
        }
      }
    }
  }
  // An array of an array: the copies of the copies; beside plain objects.
  const sol::Scene nested = sol::parse_scene(R"({"objects": [{"type": "plane_z", "c": -1},
    {"type": "array", "count": [1, 1, 3], "step": [0, 0, 1],
     "of": {"type": "array", "count": [4, 1, 1], "step": [1, 0, 0], "of": {"type": "ball", "center": [0, 0, 0], "radius": 0.2}}}]})");
  ASSERT_EQ(nested.objects.size(), 13u);
  // The twelfth ball: i = 3 of the inner array, k = 2 of the outer: (0, 0, 2)·(3, 0, 0).
  EXPECT_NEAR(glm::length(std::get<sol::Ball>(nested.objects[12].shape).center - glm::dvec3(3.0 * std::exp(2.0), 0.0, 2.0)), 0.0,
              1e-12);
  // In a quotient, as any objects of it.
  const sol::Scene golden = sol::parse_scene(R"({"quotient": "golden", "objects": [{"type": "array", "count": [2, 2, 1],
    "step": [0.5, 0.5, 0], "of": {"type": "ball", "center": [0.2, 0.2, 0.5], "radius": 0.1}}]})");
  EXPECT_EQ(golden.objects.size(), 4u);
  EXPECT_NO_THROW(sol::validate(golden));
}

TEST(Scene, ArraysNameTheirFieldInErrors) {
  const std::string ball = R"({"type": "ball", "center": [0, 0, 0], "radius": 0.1})";
  expect_rejected(R"({"objects": [{"type": "array", "count": [2, 0, 1], "step": [1, 1, 1], "of": )" + ball + "}]}",
                  "'objects[0].count' must be three integers of at least 1");
  expect_rejected(R"({"objects": [{"type": "array", "count": [2, 1.5, 1], "step": [1, 1, 1], "of": )" + ball + "}]}",
                  "'objects[0].count' must be three integers");
  expect_rejected(R"({"objects": [{"type": "array", "count": [2, 1], "step": [1, 1, 1], "of": )" + ball + "}]}",
                  "'objects[0].count' must be three integers");
  expect_rejected(R"({"objects": [{"type": "array", "count": [2, 1, 1], "of": )" + ball + "}]}", "objects[0] (an array) needs 'step'");
  expect_rejected(R"({"objects": [{"type": "array", "count": [2, 1, 1], "step": [1, 1, 1]}]})", "needs 'of'");
  expect_rejected(R"({"objects": [{"type": "array", "count": [2, 1, 1], "step": [1, 1], "of": )" + ball + "}]}",
                  "objects[0].step");
  expect_rejected(R"({"objects": [{"type": "array", "count": [2, 1, 1], "step": [1, 1, 1], "by": 2, "of": )" + ball + "}]}",
                  "unknown key 'by'");
  expect_rejected(R"({"objects": [{"type": "array", "count": [2, 1, 1], "step": [1, 1, 1], "of": {"type": "ball", "center": [0, 0, 0], "radius": -1}}]})",
                  "objects[0].of");
  expect_rejected(R"({"objects": [{"type": "array", "count": [1024, 1024, 2], "step": [1, 1, 1], "of": )" + ball + "}]}",
                  "'objects[0].count' makes more than 1048576 objects");
  expect_rejected(R"({"objects": [{"type": "sphere"}]})", "(or array: copies of an object)");
}

TEST(Scene, PresetsAreValidAndRoundTrip) {
  for (const std::string& name : sol::preset_names()) {
    const sol::Scene s = sol::preset_scene(name);
    EXPECT_NO_THROW(sol::validate(s)) << name;
    const sol::Scene back = sol::parse_scene(sol::to_json(s), name);
    EXPECT_EQ(back.camera.position, s.camera.position);
    EXPECT_EQ(back.camera.forward, s.camera.forward);
    EXPECT_EQ(back.objects.size(), s.objects.size());
    for (std::size_t k = 0; k < s.objects.size(); ++k) {
      // The kind and all its fields (c, centre, radius, axis, ...).
      EXPECT_EQ(back.objects[k].shape, s.objects[k].shape);
      EXPECT_EQ(back.objects[k].pattern, s.objects[k].pattern);
    }
    EXPECT_EQ(back.fog_density, s.fog_density);
    EXPECT_EQ(back.lights.size(), s.lights.size());
  }
  EXPECT_THROW(sol::preset_scene("nope"), sol::InvalidArgument);
  EXPECT_THROW(sol::load_scene("/nonexistent/scene.json"), sol::InvalidArgument);
}

}  // namespace
