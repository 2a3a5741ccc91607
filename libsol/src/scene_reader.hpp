// Reading a scene file's JSON with errors that say where (not installed).
//
// nlohmann::json keeps no positions, so the reader first indexes where each
// value of the text starts (line and column, by its path: "camera.fov",
// "objects[2].radius"); every error it raises names its source and the
// place of the field concerned: "scene.json: objects[1].radius must be
// finite and > 0 (line 6, column 6)". The reader is passed down explicitly:
// no global state, so parses on several threads never meet.
#pragma once

#include <initializer_list>
#include <map>
#include <string>
#include <string_view>
#include <utility>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

namespace sol::detail {

using nlohmann::json;

/// Where a value starts in the text (1-based).
struct FilePlace {
  int line = 1, column = 1;
};

/// Refuses what the JSON parser is not asked to bear: nesting deeper than
/// kSceneFileMaxDepth (it recurses per level) and NUL bytes (it would stop at
/// one and ignore what follows); InvalidArgument "<source>: ... (line L, column C)".
void check_json_text(std::string_view text, std::string_view source);

/// A file's whole text; InvalidArgument "<path>: cannot open <kind> file" or "cannot read".
std::string read_text_file(const std::string& path, const char* kind);

class SceneFileReader {
 public:
  /// The most of a value that a message quotes.
  static constexpr std::size_t kShownBytes = 64;

  /// Indexes `text` (which must already have parsed as JSON); `source` (a
  /// file name) prefixes every message.
  SceneFileReader(std::string_view text, std::string_view source);
  /// The source the messages name (a scene file's name, or a label).
  std::string_view source() const { return m_source; }

  /// Throws InvalidArgument "<source>: <what> (line L, column C)", the place
  /// of `path`'s value (or of the nearest enclosing value the file has).
  [[noreturn]] void fail(const std::string& path, const std::string& what) const;

  /// A finite number; `path` names it in errors.
  double number(const json& value, const std::string& path) const;
  /// An array of three finite numbers.
  glm::dvec3 vec3(const json& value, const std::string& path) const;
  /// true or false.
  bool boolean(const json& value, const std::string& path) const;
  /// Fails on a key of `object` that is not in `keys`; `what` names the
  /// object in the message ("objects[0] (a ball)"), `path` is its path.
  void require_known_keys(const json& object, std::initializer_list<std::string_view> keys, const std::string& what,
                          const std::string& path) const;
  /// The same for an object of a scene: its kind's `keys`, then the keys
  /// every object takes (kObjectKeys: its appearance and material).
  void require_known_object_keys(const json& object, std::initializer_list<std::string_view> keys, const std::string& what,
                                 const std::string& path) const;
  /// Fails unless `object` has `key`: "<what> needs <noun>".
  void require_key(const json& object, const char* key, const std::string& what, const std::string& noun,
                   const std::string& path) const;

  /// The value of the entry of `options` that `value` (a string) names;
  /// fails "'<path>' must be a, b or c, got '<value>'" otherwise.
  template <class T>
  T choice(const json& value, const std::string& path,
           std::initializer_list<std::pair<std::string_view, T>> options) const {
    if (value.is_string()) {
      for (const auto& [name, result] : options) {
        if (value.get_ref<const std::string&>() == name) return result;
      }
    }
    std::string names;
    std::size_t i = 0;
    for (const auto& option : options) {
      names += i == 0 ? "" : (i + 1 == options.size() ? " or " : ", ");
      names += option.first;
      ++i;
    }
    fail(path, "'" + path + "' must be " + names + ", got " + json_text(value));
  }

  /// A string value as it is, anything else as its JSON text (for names),
  /// shortened as shown().
  static std::string text(const json& value);
  /// The value as its JSON text for a message: a string quoted ("4", not
  /// 4), bytes that are not UTF-8 as U+FFFD; shortened as shown().
  static std::string json_text(const json& value);
  /// `s` for a message: bytes that are not UTF-8 and control characters
  /// written as \xNN (a message is text, whatever the file held); beyond
  /// `limit` bytes cut (at a UTF-8 character), with its length ("abc...
  /// (5000000 bytes)"), so a huge value does not flood the terminal.
  static std::string shown(std::string s, std::size_t limit = kShownBytes);

 private:
  std::string_view m_source;
  std::map<std::string, FilePlace> m_places;
};

}  // namespace sol::detail
