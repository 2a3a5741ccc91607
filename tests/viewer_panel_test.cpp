// The panel's texture controls (viewer/panel.hpp, texture_controls) driven
// through ImGui without a window or a backend, as a user would: the file
// typed into the field and Enter pressed, a missing file typed, the "no
// texture" button clicked. ImGui runs on the CPU alone here: a context
// with a display size, its font atlas built, keys mapped (the 1.86 IO:
// io.KeyMap and io.KeysDown), one NewFrame/Render per frame.
#include <array>
#include <filesystem>
#include <memory>
#include <string>

#include <gtest/gtest.h>
#include <imgui.h>
#include <sol/sol.hpp>

#include "panel.hpp"

namespace {

constexpr int kEnter = 13, kBackspace = 8;  // our indices into io.KeysDown

// A reader that knows one image: any "*.png" but "missing.png" is a 2 x 1
// texture, red then blue; the paths it was asked for are noted.
std::vector<std::string> g_asked;
sol::Texture two_texels(const std::string& path) {
  g_asked.push_back(path);
  if (std::filesystem::path(path).filename() == "missing.png") throw sol::InvalidArgument(path + ": no such file");
  sol::Texture t;
  t.width = 2;
  t.height = 1;
  t.rgb = {1.0f, 0.0f, 0.0f, 0.0f, 0.0f, 1.0f};
  return t;
}

// ImGui without a window: each frame() draws the object's texture controls
// in a window with the input queued since the last frame.
class Frames {
 public:
  Frames() {
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.DisplaySize = ImVec2(800.0f, 600.0f);
    io.DeltaTime = 1.0f / 60.0f;
    io.IniFilename = nullptr;
    unsigned char* pixels = nullptr;
    int w = 0, h = 0;
    io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);  // (the atlas built: NewFrame needs it)
    io.KeyMap[ImGuiKey_Enter] = kEnter;
    io.KeyMap[ImGuiKey_Backspace] = kBackspace;
  }
  ~Frames() { ImGui::DestroyContext(); }
  Frames(const Frames&) = delete;
  Frames& operator=(const Frames&) = delete;

  // One frame; the keyboard focus put on the file field first if `focus`.
  // Whether the controls changed the object; `button` the last widget's
  // rectangle (the "no texture" button where there is a texture).
  bool frame(sol::SceneObject& o, bool focus = false) {
    ImGui::NewFrame();
    ImGui::SetNextWindowPos(ImVec2(0.0f, 0.0f));
    ImGui::SetNextWindowSize(ImVec2(600.0f, 400.0f));
    ImGui::Begin("object");
    if (focus) ImGui::SetKeyboardFocusHere();
    slider_width = ImGui::CalcItemWidth();
    const bool changed = sol::viewer::texture_controls(o);
    button_min = ImGui::GetItemRectMin();
    button_max = ImGui::GetItemRectMax();
    ImGui::End();
    ImGui::Render();
    return changed;
  }
  // Puts the keyboard focus on the file field (asked in one frame, taken
  // in the next).
  bool focus(sol::SceneObject& o) { return frame(o, true) | frame(o); }
  // Types `text` into the focused field (one frame) and presses Enter
  // (down one frame, up the next): whether a frame changed the object.
  bool type_and_enter(sol::SceneObject& o, const std::string& text) {
    ImGuiIO& io = ImGui::GetIO();
    io.AddInputCharactersUTF8(text.c_str());
    bool changed = frame(o);
    io.KeysDown[kEnter] = true;
    changed |= frame(o);
    io.KeysDown[kEnter] = false;
    changed |= frame(o);
    return changed;
  }
  // Clears the focused field: Backspace pressed and released n times.
  void erase(sol::SceneObject& o, int n) {
    ImGuiIO& io = ImGui::GetIO();
    for (int k = 0; k < n; ++k) {
      io.KeysDown[kBackspace] = true;
      frame(o);
      io.KeysDown[kBackspace] = false;
      frame(o);
    }
  }
  // Clicks the left button at the centre of the last frame's `button`
  // (moved there one frame, pressed the next, released the one after).
  bool click_button(sol::SceneObject& o) {
    return click_at(o, ImVec2(0.5f * (button_min.x + button_max.x), 0.5f * (button_min.y + button_max.y)));
  }
  // Clicks the cells slider (the widget on the line above the button)
  // at `share` of the width of its first (x) or second (y) half: a
  // slider's value follows the mouse along it.
  bool click_cells(sol::SceneObject& o, bool second, float share) {
    const ImGuiStyle& style = ImGui::GetStyle();
    const float width = 0.5f * (slider_width - style.ItemInnerSpacing.x);
    const float left = button_min.x + (second ? width + style.ItemInnerSpacing.x : 0.0f);
    const float y = button_min.y - style.ItemSpacing.y - 0.5f * ImGui::GetFrameHeight();
    return click_at(o, ImVec2(left + share * width, y));
  }
  bool click_at(sol::SceneObject& o, ImVec2 where) {
    ImGuiIO& io = ImGui::GetIO();
    io.MousePos = where;
    bool changed = frame(o);
    io.MouseDown[0] = true;
    changed |= frame(o);
    io.MouseDown[0] = false;
    changed |= frame(o);
    return changed;
  }

  ImVec2 button_min, button_max;
  float slider_width = 0.0f;  // the window's item width: the cells slider's two halves and their spacing
};

TEST(Panel, ATextureTypedIsReadThroughTheProgramsReaderItsCellsSetAndTakenOffByItsButton) {
  sol::set_texture_reader(two_texels);
  g_asked.clear();
  sol::SceneObject o{sol::Ball{{0.0, 0.0, 0.0}, 0.5}, {1.0, 1.0, 1.0}};
  Frames frames;
  EXPECT_FALSE(frames.focus(o));  // nothing typed yet

  // A file typed and Enter: read (by the path typed), named by its absolute
  // path, at one copy per cell as before.
  EXPECT_TRUE(frames.type_and_enter(o, "globe.png"));
  ASSERT_TRUE(o.texture);
  EXPECT_EQ(o.texture->width, 2);
  EXPECT_EQ(o.texture->height, 1);
  EXPECT_EQ(o.texture->file, std::filesystem::absolute("globe.png").lexically_normal().string());
  ASSERT_EQ(g_asked.size(), 1u);
  EXPECT_EQ(g_asked[0], "globe.png");
  EXPECT_EQ(o.texture_cells, glm::dvec2(1.0, 1.0));
  const std::shared_ptr<const sol::Texture> read = o.texture;

  // A missing file: its error shown, the texture kept, nothing changed.
  // (Enter left the field: focused again, its text erased.)
  frames.focus(o);
  frames.erase(o, static_cast<int>(std::string("globe.png").size()));
  EXPECT_FALSE(frames.type_and_enter(o, "missing.png"));
  ASSERT_EQ(g_asked.size(), 2u);
  EXPECT_EQ(g_asked[1], "missing.png");
  EXPECT_EQ(o.texture, read);

  // The cells slider, as powers of two from 1/16 to 64: its x half
  // clicked at its right end sets 64 cells across, its y half at its left
  // end 1/16; the texture stays.
  frames.frame(o);
  EXPECT_TRUE(frames.click_cells(o, false, 0.98f));
  EXPECT_EQ(o.texture_cells, glm::dvec2(64.0, 1.0));
  EXPECT_TRUE(frames.click_cells(o, true, 0.02f));
  EXPECT_EQ(o.texture_cells, glm::dvec2(64.0, 1.0 / 16.0));
  EXPECT_EQ(o.texture, read);

  // The "no texture" button (the last widget drawn) takes it off.
  frames.frame(o);
  EXPECT_TRUE(frames.click_button(o));
  EXPECT_FALSE(o.texture);
  EXPECT_FALSE(frames.frame(o));  // and it stays off
  EXPECT_FALSE(o.texture);
  sol::set_texture_reader({});
}

}  // namespace
