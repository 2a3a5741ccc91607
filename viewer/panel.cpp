#include "panel.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <span>
#include <string>
#include <variant>

#include <imgui.h>

#include <sol/lattice.hpp>
#include <sol/objects.hpp>
#include <sol/texture.hpp>

namespace sol::viewer {
namespace {

// Edits on doubles through ImGui's scalar widgets (ImGuiDataType_Double): no float rounding of the scene.
bool drag_double(const char* label, double& v, double speed, double lo, double hi, const char* format = "%.4g") {
  return ImGui::DragScalar(label, ImGuiDataType_Double, &v, static_cast<float>(speed), &lo, &hi, format,
                           ImGuiSliderFlags_AlwaysClamp);
}
bool input_vec3(const char* label, glm::dvec3& v) {
  return ImGui::InputScalarN(label, ImGuiDataType_Double, &v.x, 3, nullptr, nullptr, "%.4g",
                             ImGuiInputTextFlags_EnterReturnsTrue);
}
bool color_edit(const char* label, glm::dvec3& c) {
  float f[3] = {static_cast<float>(c.x), static_cast<float>(c.y), static_cast<float>(c.z)};
  if (!ImGui::ColorEdit3(label, f, ImGuiColorEditFlags_Float)) return false;
  c = glm::dvec3(std::clamp(f[0], 0.0f, 1.0f), std::clamp(f[1], 0.0f, 1.0f), std::clamp(f[2], 0.0f, 1.0f));
  return true;
}

const char* const kPatterns[] = {"none", "circles", "checker"};

}  // namespace

// (Each object's field is kept by its widget's ID.)
bool texture_controls(SceneObject& o) {
  bool changed = false;
  struct Entry {
    std::array<char, 512> text{};
    std::string error;
  };
  static std::map<ImGuiID, Entry> entries;  // each object's field, by its widget's ID
  Entry& e = entries[ImGui::GetID("texture file")];
  if (e.text[0] == '\0' && o.texture) std::snprintf(e.text.data(), e.text.size(), "%s", o.texture->file.c_str());
  if (ImGui::InputText("texture file", e.text.data(), e.text.size(), ImGuiInputTextFlags_EnterReturnsTrue)) {
    try {
      const std::string file = e.text.data();
      std::error_code ec;
      o.texture = file.empty() ? nullptr : read_texture(file, std::filesystem::absolute(file, ec).lexically_normal().string());
      e.error.clear();
      changed = true;
    } catch (const std::exception& error) {
      e.error = error.what();
    }
  }
  if (!e.error.empty()) ImGui::TextWrapped("%s", e.error.c_str());
  if (!o.texture) return changed;
  ImGui::Text("%d x %d texels", o.texture->width, o.texture->height);
  // Cells as exponents of two, -4 .. 6 (1/16 .. 64: sol::validate_texture_cells).
  int exponents[2] = {static_cast<int>(std::lround(std::log2(o.texture_cells.x))),
                      static_cast<int>(std::lround(std::log2(o.texture_cells.y)))};
  if (ImGui::SliderInt2("texture cells (2^n)", exponents, -4, 6)) {
    o.texture_cells = {std::ldexp(1.0, exponents[0]), std::ldexp(1.0, exponents[1])};
    changed = true;
  }
  if (ImGui::Button("no texture")) {
    o.texture = nullptr;
    e.text[0] = '\0';
    changed = true;
  }
  return changed;
}

namespace {

bool object_controls(SceneObject& o) {
  bool changed = color_edit("colour", o.color);
  int pattern = static_cast<int>(o.pattern);
  if (ImGui::Combo("pattern", &pattern, kPatterns, 3)) {
    o.pattern = static_cast<Pattern>(pattern);
    changed = true;
  }
  // The kind's own parameters, as it lists them (visit_fields).
  struct FieldControls {
    bool& changed;
    void operator()(const char* name, glm::dvec3& v) { changed |= input_vec3(name, v); }
    void operator()(const char* name, double& v, const FieldRange& r) { changed |= drag_double(name, v, r.speed, r.lo, r.hi); }
    void operator()(const char* name, bool& v) { changed |= ImGui::Checkbox(name, &v); }
  };
  std::visit([&](auto& kind) { kind.visit_fields(FieldControls{changed}); }, o.shape);
  if (!is_solid(o.shape)) changed |= ImGui::Checkbox("cutout (only the bright cells)", &o.cutout);
  // The material (one of SOL_MATERIALS), the diffuse one's mirror share, the glossy one's roughness, the glass one's index
  // and the emitted radiance (every material's; linear, may exceed 1).
  const std::span<const Material> all = materials();
  if (ImGui::BeginCombo("material", std::string(to_string(o.material)).c_str())) {
    for (const Material m : all) {
      if (ImGui::Selectable(std::string(to_string(m)).c_str(), m == o.material) && m != o.material) {
        o.material = m;
        if (m != Material::Diffuse) o.mirror = 0.0;  // (the diffuse material's share alone)
        o.roughness = m == Material::Glossy ? SceneObject::kDefaultRoughness : 0.0;  // (the glossy one's alone)
        o.ior = m == Material::Glass ? SceneObject::kDefaultIor : 0.0;                // (the glass one's alone)
        changed = true;
      }
    }
    ImGui::EndCombo();
  }
  if (o.material == Material::Diffuse) changed |= drag_double("mirror", o.mirror, 0.01, 0.0, 1.0, "%.2f");
  if (o.material == Material::Glossy) changed |= drag_double("roughness", o.roughness, 0.005, 0.0, 1.0, "%.3f");
  if (o.material == Material::Glass) changed |= drag_double("index of refraction", o.ior, 0.005, 1.0, 3.0, "%.3f");
  float e[3] = {static_cast<float>(o.emission.x), static_cast<float>(o.emission.y), static_cast<float>(o.emission.z)};
  if (ImGui::DragFloat3("emission", e, 0.01f, 0.0f, 100.0f, "%.2f")) {
    o.emission = glm::dvec3(std::max(e[0], 0.0f), std::max(e[1], 0.0f), std::max(e[2], 0.0f));
    changed = true;
  }
  changed |= texture_controls(o);
  return changed;
}

bool light_controls(Light& l) {
  bool changed = false;
  int type = l.type == LightType::Directional ? 0 : 1;
  const char* const types[] = {"directional", "point"};
  if (ImGui::Combo("type", &type, types, 2)) {
    l.type = type == 0 ? LightType::Directional : LightType::Point;
    changed = true;
  }
  if (l.type == LightType::Directional) {
    changed |= input_vec3("towards the light", l.direction);
  } else {
    changed |= input_vec3("position", l.position);
    changed |= ImGui::Checkbox("exact (along the true geodesics)", &l.exact);
  }
  changed |= color_edit("colour", l.color);
  changed |= drag_double("intensity", l.intensity, 0.01, 0.0, 1e3);
  return changed;
}

std::string format_vec(const char* name, const glm::dvec3& v) {
  char line[160];
  std::snprintf(line, sizeof line, "%s (%.4f, %.4f, %.4f)", name, v.x, v.y, v.z);
  return line;
}

}  // namespace

namespace {

// The panel's four integers as a monodromy, and back.
Monodromy to_monodromy(const std::array<int, 4>& a) { return {a[0], a[1], a[2], a[3]}; }

std::array<int, 4> from_monodromy(const Monodromy& a) {
  auto small = [](long long v) { return static_cast<int>(std::clamp(v, -1000000LL, 1000000LL)); };
  return {small(a.a), small(a.b), small(a.c), small(a.d)};
}

}  // namespace

std::string quotient_refusal(const World& world) {
  World q = world;
  q.space = GoldenSpace{};
  try {
    validate(q);
  } catch (const std::exception& e) {
    return e.what();
  }
  return {};
}

// The readouts: rate, frame times, refinement, steps, the observer and its
// copy of the domain, the last message.
void draw_readouts(const PanelModel& m) {
  char line[256];
  // (Two lines: one was cut at the panel's edge.)
  std::snprintf(line, sizeof line, "%.1f fps  %.2f M rays/s (rendered frames)", m.fps, m.rays_per_second * 1e-6);
  ImGui::TextUnformatted(line);
  std::snprintf(line, sizeof line, "%dx%d, scale %.2f%s", m.render_width, m.render_height, m.scale, m.adaptive ? ", adaptive" : "");
  ImGui::TextUnformatted(line);
  if (!m.frame_ms.empty()) {
    const float worst = *std::max_element(m.frame_ms.begin(), m.frame_ms.end());
    std::snprintf(line, sizeof line, "frame %.1f ms (worst %.1f)", m.frame_ms.back(), worst);
    ImGui::PlotLines("##frames", m.frame_ms.data(), static_cast<int>(m.frame_ms.size()), 0, line, 0.0f,
                     std::max(worst, 1.0f) * 1.1f, ImVec2(340, 48));
  }
  if (m.refine_target > 0) {
    if (m.refined < 0) {
      std::snprintf(line, sizeof line, "moving: rendering at scale %.2f", m.scale);
    } else if (m.refined < m.refine_target) {
      std::snprintf(line, sizeof line, "still: refining, %d of %d samples per pixel", m.refined, m.refine_target);
    } else {
      std::snprintf(line, sizeof line, "still: refined, %d samples per pixel", m.refine_target);
    }
    ImGui::TextUnformatted(line);
  }
  if (m.mean_steps >= 0) {
    std::snprintf(line, sizeof line, "mean march steps %.1f", m.mean_steps);
    ImGui::TextUnformatted(line);
  }
  if (m.clipped > 0) {  // (exposure and tone: the camera section)
    std::snprintf(line, sizeof line, "clipped at white: %.1f %% of pixels", 100.0 * m.clipped);
    ImGui::TextUnformatted(line);
  }

  ImGui::TextUnformatted(format_vec("position", m.observer.position()).c_str());
  ImGui::TextUnformatted(format_vec("forward ", m.observer.forward()).c_str());
  ImGui::TextUnformatted(format_vec("up      ", m.observer.up()).c_str());
  if (m.observer.lattice()) {
    // The default font has ASCII only: γ1 is written g1.
    // The copy w·D of the fundamental domain the observer is in (the default font is ASCII: γ1 is g1).
    const LatticeWord& w = m.observer.copy();
    std::string word;
    const std::pair<const char*, long long> factors[] = {{"g1", w.a}, {"g2", w.b}, {"g3", w.c}};
    for (const auto& [name, power] : factors) {
      if (power == 0) continue;
      std::snprintf(line, sizeof line, "%s%s^%lld", word.empty() ? "" : " ", name, power);
      word += line;
    }
    const std::string copy = !m.observer.copy_known() ? std::string("copy of the domain D: too far to count")
                             : "copy of the domain D: " + (word.empty() ? std::string("e") : word) + " D";
    ImGui::TextUnformatted(copy.c_str());
  }
  if (!m.message.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.55f, 0.4f, 1.0f));
    ImGui::TextWrapped("%s", m.message.c_str());
    ImGui::PopStyleColor();
  }
}

  // The space: Sol, the golden quotient, the torus bundle of a monodromy
  // typed in (applied on Enter), a z loop or xy loops; tubes along γ1, γ2
  // follow the lattice. A space the objects do not fit is not applied,
  // and the reason is shown.
void space_controls(PanelModel& m, PanelText& text, PanelActions& out) {
  char line[256];
  int quotient = static_cast<int>(m.scene.quotient());
  const char* const quotients[] = {"none (Sol)", "golden (Gamma\\Sol)", "monodromy A", "z loop (Sol/<(0, 0, h)>)",
                                   "xy loops (torus x line)"};
  static_assert(std::size(quotients) == std::variant_size_v<Space>, "a label for each space of sol/spaces.hpp");
  auto apply_space = [&](const Space& space) {
    try {
      Scene next = m.scene;
      set_space(next, space);
      validate(next);
      m.scene = std::move(next);
      text.refusal.clear();
      out.world_changed = true;
    } catch (const std::exception& e) {
      text.refusal = e.what();
    }
  };
  if (ImGui::Combo("quotient", &quotient, quotients, static_cast<int>(std::size(quotients)))) {
    Space space = default_space(static_cast<Quotient>(quotient));
    if (auto* bundle = std::get_if<MonodromySpace>(&space)) bundle->monodromy = to_monodromy(text.monodromy);
    apply_space(space);
  }
  if (const auto* z = std::get_if<ZLoopSpace>(&m.scene.space)) {
    ZLoopSpace next = *z;
    if (drag_double("loop height h", next.height, 0.01, 1.0, 20.0, "%.3f")) apply_space(next);
  }
  if (const auto* xy = std::get_if<XYLoopsSpace>(&m.scene.space)) {
    XYLoopsSpace next = *xy;
    double loops[4] = {next.loops[0].x, next.loops[0].y, next.loops[1].x, next.loops[1].y};
    if (ImGui::InputScalarN("gamma1, gamma2 (x, y)", ImGuiDataType_Double, loops, 4, nullptr, nullptr, "%.3f",
                            ImGuiInputTextFlags_EnterReturnsTrue)) {
      next.loops = {glm::dvec2(loops[0], loops[1]), glm::dvec2(loops[2], loops[3])};
      apply_space(next);
    }
  }
  if (m.scene.quotient() != Quotient::Monodromy && !text.refusal.empty()) {
    ImGui::TextWrapped("not applied: %s", text.refusal.c_str());
  }
  if (const auto* shown = std::get_if<MonodromySpace>(&m.scene.space)) {
    bool apply = ImGui::InputInt4("A = [[a, b], [c, d]]", text.monodromy.data(), ImGuiInputTextFlags_EnterReturnsTrue);
    bool custom_area = shown->fibre_area.has_value();
    double area = shown->fibre_area.value_or(m.scene.lattice() ? m.scene.lattice()->fibre_area() : 1.0);
    if (ImGui::Checkbox("fibre area", &custom_area)) apply = true;
    if (custom_area) {
      ImGui::SameLine();
      apply |= drag_double("##area", area, 0.01, 0.5, 100.0, "%.3f");
    }
    if (apply) {
      apply_space(MonodromySpace{.monodromy = to_monodromy(text.monodromy),
                                 .fibre_area = custom_area ? std::optional<double>(area) : std::nullopt});
    }
    const Monodromy& a = std::get<MonodromySpace>(m.scene.space).monodromy;  // as applied
    std::snprintf(line, sizeof line, "shown: [[%lld, %lld], [%lld, %lld]], trace %lld, h = ln lambda = %.4f", a.a, a.b, a.c,
                  a.d, a.trace(), m.scene.lattice() ? m.scene.lattice()->height() : 0.0);
    ImGui::TextUnformatted(line);
    if (!text.refusal.empty()) ImGui::TextWrapped("not applied: %s", text.refusal.c_str());
  } else {
    text.monodromy = from_monodromy(Monodromy{});
  }
  if (m.scene.quotient() == Quotient::None) {
    const std::string why = quotient_refusal(m.scene);
    if (!why.empty()) ImGui::TextWrapped("golden quotient not possible: %s", why.c_str());
  }
}

PanelActions draw_panel(PanelModel& m, PanelText& text) {
  PanelActions out;
  ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(360, 0), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowBgAlpha(0.85f);
  if (!ImGui::Begin("solview (F1)", nullptr, ImGuiWindowFlags_NoSavedSettings)) {
    ImGui::End();
    return out;
  }
  ImGui::PushItemWidth(180);
  draw_readouts(m);

  // ---- Actions
  if (ImGui::Button("screenshot")) out.screenshot = true;
  ImGui::SameLine();
  if (ImGui::Button(m.recording ? "stop recording" : "record")) out.toggle_recording = true;
  ImGui::SameLine();
  if (ImGui::Button("reset camera")) out.reset = true;
  if (ImGui::Button("copy solrender options")) out.copy_options = true;
  ImGui::SameLine();
  if (ImGui::Button("copy scene JSON")) out.copy_json = true;
  ImGui::InputText("##save", text.save.data(), text.save.size());
  ImGui::SameLine();
  if (ImGui::Button("save scene") && text.save[0] != '\0') out.save = std::string(text.save.data());

  // ---- Camera and rendering
  if (ImGui::CollapsingHeader("camera and rendering", ImGuiTreeNodeFlags_DefaultOpen)) {
    drag_double("fov (degrees)", m.scene.camera.fov, 0.2, 1.0, 179.0, "%.1f");
    // The camera aimed at a point: along the minimising geodesic's start, not the coordinate difference.
    ImGui::InputScalarN("##look_at", ImGuiDataType_Double, text.look_at.data(), 3, nullptr, nullptr, "%.3f");
    ImGui::SameLine();
    if (ImGui::Button("look at")) out.look_at = glm::dvec3(text.look_at[0], text.look_at[1], text.look_at[2]);
    // Depth of field (sol/lens.hpp): seen as the refinement's samples gather (a moving view is the pinhole's).
    drag_double("aperture", m.scene.camera.aperture, 0.001, 0.0, 1.0, "%.3f");
    drag_double("focus distance", m.scene.camera.focus_distance, 0.01, 0.01, 100.0, "%.3f");
    // The display: how the linear frame is shown (not a change of the world: nothing is rendered again).
    drag_double("exposure (stops)", m.scene.display.exposure, 0.05, -Display::kMaxExposure, Display::kMaxExposure, "%+.2f");
    int tone = static_cast<int>(m.scene.display.tone);
    const char* const tones[] = {
#define SOL_TONE_LABEL(Enum, code_name, code, name) name,
        SOL_TONE_CURVES(SOL_TONE_LABEL)
#undef SOL_TONE_LABEL
    };
    if (ImGui::Combo("tone curve", &tone, tones, IM_ARRAYSIZE(tones))) m.scene.display.tone = static_cast<Tone>(tone);
    out.world_changed |= drag_double("max distance", m.scene.max_distance, 0.1, 0.1, 1e3, "%.2f");
    int steps = m.scene.max_steps;
    if (ImGui::DragInt("max steps", &steps, 1.0f, 1, 10000, "%d", ImGuiSliderFlags_AlwaysClamp)) {
      m.scene.max_steps = steps;
      out.world_changed = true;
    }
    out.world_changed |= drag_double("hit epsilon", m.scene.hit_epsilon, 1e-6, 1e-7, 0.1, "%.2e");
    // (Shown as it renders here: mirrors' reflections, or paths' scatterings when the view refines by paths.)
    int bounces = m.refine_paths ? m.scene.path_bounces() : m.scene.mirror_bounces();
    if (ImGui::DragInt(m.refine_paths ? "max bounces (paths)" : "max bounces (mirrors)", &bounces, 0.1f, 0, 64, "%d",
                       ImGuiSliderFlags_AlwaysClamp)) {
      m.scene.max_bounces = bounces;
      out.world_changed = true;
    }
    ImGui::Checkbox("stereo", &m.stereo);
    drag_double("ipd", m.ipd, 0.001, 0.0, 10.0, "%.3f");
    if (drag_double("render scale", m.scale, 0.005, m.min_scale, 1.0, "%.2f")) m.adaptive = false;
    ImGui::Checkbox("adaptive scale, target fps", &m.adaptive);
    drag_double("##target", m.target_fps, 0.2, 1.0, 240.0, "%.0f fps");
  }

  // ---- Scene
  if (ImGui::CollapsingHeader("scene", ImGuiTreeNodeFlags_DefaultOpen)) {
    int current = -1;
    for (std::size_t i = 0; i < m.presets.size(); ++i) {
      if (m.presets[i] == m.scene_name) current = static_cast<int>(i);
    }
    if (ImGui::BeginCombo("preset", current >= 0 ? m.presets[static_cast<std::size_t>(current)].c_str() : "(file)")) {
      for (const std::string& p : m.presets) {
        if (ImGui::Selectable(p.c_str(), p == m.scene_name)) out.load = p;
      }
      ImGui::EndCombo();
    }
    ImGui::InputText("##file", text.file.data(), text.file.size());
    ImGui::SameLine();
    if (ImGui::Button("load file") && text.file[0] != '\0') out.load = std::string(text.file.data());

    space_controls(m, text, out);
    out.world_changed |= drag_double("ambient", m.scene.ambient, 0.005, 0.0, 1.0, "%.3f");
    out.world_changed |= drag_double("fog density", m.scene.fog_density, 0.001, 0.0, 10.0, "%.3f");
    out.world_changed |= color_edit("fog colour", m.scene.fog_color);
    char line[64];
    for (std::size_t i = 0; i < m.scene.objects.size(); ++i) {
      ImGui::PushID("object");
      ImGui::PushID(static_cast<int>(i));
      SceneObject& o = m.scene.objects[i];
      std::snprintf(line, sizeof line, "object %zu: %s", i + 1, std::string(kind_name(o.shape)).c_str());
      if (ImGui::TreeNode(line)) {
        out.world_changed |= object_controls(o);
        ImGui::TreePop();
      }
      ImGui::PopID();
      ImGui::PopID();
    }
    for (std::size_t i = 0; i < m.scene.lights.size(); ++i) {
      ImGui::PushID("light");
      ImGui::PushID(static_cast<int>(i));
      std::snprintf(line, sizeof line, "light %zu", i + 1);
      if (ImGui::TreeNode(line)) {
        out.world_changed |= light_controls(m.scene.lights[i]);
        ImGui::TreePop();
      }
      ImGui::PopID();
      ImGui::PopID();
    }
  }
  ImGui::PopItemWidth();
  const ImVec2 at = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
  text.rect = {at.x, at.y, size.x, size.y};
  ImGui::End();
  return out;
}

}  // namespace sol::viewer
