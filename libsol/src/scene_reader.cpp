#include "scene_reader.hpp"

#include <algorithm>
#include <iterator>
#include <vector>

#include "sol/file_io.hpp"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string_view>
#include <vector>

#include "sol/error.hpp"
#include "sol/scene_file.hpp"  // kSceneFileMaxDepth

namespace sol::detail {
namespace {

// Scans JSON text (known to be valid) and records where each value starts.
// Iterative: one frame per open object or array, however deep the text.
class PlaceScanner {
 public:
  PlaceScanner(std::string_view text, std::map<std::string, FilePlace>& places)
      : m_text(text), m_places(places) {}

  void run() {
    value("");
    while (!m_frames.empty()) {
      skip_space();
      if (!more()) return;
      Frame& f = m_frames.back();
      const char c = m_text[m_pos];
      if (c == (f.array ? ']' : '}')) {
        ++m_pos;
        m_frames.pop_back();
      } else if (c == ',') {
        ++m_pos;
      } else if (f.array) {
        const std::string path = f.path + "[" + std::to_string(f.next_index++) + "]";
        value(path);
      } else {
        const std::string key = string();
        skip_space();
        if (more() && m_text[m_pos] == ':') ++m_pos;
        const std::string path = f.path.empty() ? key : f.path + "." + key;
        value(path);
      }
    }
  }

 private:
  struct Frame {
    std::string path;
    bool array = false;
    int next_index = 0;
  };

  bool more() const { return m_pos < m_text.size(); }
  void skip_space() {
    while (more() && std::isspace(static_cast<unsigned char>(m_text[m_pos]))) {
      if (m_text[m_pos] == '\n') {
        ++m_line;
        m_line_start = m_pos + 1;
      }
      ++m_pos;
    }
  }
  std::string string() {
    std::string out;
    ++m_pos;  // opening quote
    while (more() && m_text[m_pos] != '"') {
      if (m_text[m_pos] == '\\' && m_pos + 1 < m_text.size()) ++m_pos;
      out += m_text[m_pos++];
    }
    ++m_pos;  // closing quote
    return out;
  }
  // Records the value at m_pos under `path`, and opens a frame for an object or array.
  void value(const std::string& path) {
    skip_space();
    if (!more()) return;
    m_places.emplace(path, FilePlace{m_line, static_cast<int>(m_pos - m_line_start) + 1});
    const char c = m_text[m_pos];
    if (c == '{' || c == '[') {
      ++m_pos;
      m_frames.push_back({path, c == '[', 0});
    } else if (c == '"') {
      string();
    } else {
      while (more() && std::string_view(",}] \t\r\n").find(m_text[m_pos]) == std::string_view::npos) ++m_pos;
    }
  }

  std::string_view m_text;
  std::map<std::string, FilePlace>& m_places;
  std::vector<Frame> m_frames;
  std::size_t m_pos = 0, m_line_start = 0;
  int m_line = 1;
};

}  // namespace

SceneFileReader::SceneFileReader(std::string_view text, std::string_view source) : m_source(source) {
  PlaceScanner(text, m_places).run();
}

void SceneFileReader::fail(const std::string& path, const std::string& what) const {
  // The field's own place, else its nearest enclosing value's ("objects[0]"
  // for a key it lacks).
  std::string at = path;
  for (;;) {
    const auto it = m_places.find(at);
    if (it != m_places.end()) {
      throw InvalidArgument(std::string(m_source) + ": " + what + " (line " + std::to_string(it->second.line) +
                            ", column " + std::to_string(it->second.column) + ")");
    }
    const std::size_t cut = at.find_last_of(".[");
    if (at.empty() || cut == std::string::npos) break;
    at.resize(cut);
  }
  throw InvalidArgument(std::string(m_source) + ": " + what);
}

namespace {

// The length of the UTF-8 sequence at s[i] (1 to 4), or 0 where the bytes
// there are not one (a stray continuation, an overlong form, a surrogate,
// beyond U+10FFFF, cut short).
std::size_t utf8_sequence(std::string_view s, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char c = byte(i);
  if (c < 0x80) return 1;
  const std::size_t n = c >= 0xC2 && c <= 0xDF ? 2 : c >= 0xE0 && c <= 0xEF ? 3 : c >= 0xF0 && c <= 0xF4 ? 4 : 0;
  if (n == 0 || i + n > s.size()) return 0;
  for (std::size_t k = 1; k < n; ++k) {
    if ((byte(i + k) & 0xC0) != 0x80) return 0;
  }
  const unsigned char second = byte(i + 1);
  if ((c == 0xE0 && second < 0xA0) || (c == 0xED && second > 0x9F) || (c == 0xF0 && second < 0x90) ||
      (c == 0xF4 && second > 0x8F)) {
    return 0;
  }
  return n;
}

// s with every byte that is not part of a UTF-8 character, and every ASCII
// control character but none, as \xNN.
std::string printable(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (std::size_t i = 0; i < s.size();) {
    const std::size_t n = utf8_sequence(s, i);
    const auto c = static_cast<unsigned char>(s[i]);
    if (n == 0 || (n == 1 && (c < 0x20 || c == 0x7F))) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\x%02X", c);
      out += escaped;
      ++i;
    } else {
      out.append(s.substr(i, n));
      i += n;
    }
  }
  return out;
}

}  // namespace

std::string SceneFileReader::shown(std::string s, std::size_t limit) {
  s = printable(s);
  if (s.size() <= limit) return s;
  const std::size_t total = s.size();
  s.resize(limit);
  // Not half a UTF-8 character: drop a cut sequence's bytes.
  while (!s.empty() && (static_cast<unsigned char>(s.back()) & 0xC0) == 0x80) s.pop_back();
  if (!s.empty() && static_cast<unsigned char>(s.back()) >= 0xC0) s.pop_back();
  return s + "... (" + std::to_string(total) + " bytes)";
}

std::string SceneFileReader::text(const json& value) {
  return shown(value.is_string() ? value.get<std::string>() : json_text(value));
}

std::string SceneFileReader::json_text(const json& value) {
  return shown(value.dump(-1, ' ', false, json::error_handler_t::replace));
}

double SceneFileReader::number(const json& value, const std::string& path) const {
  if (!value.is_number()) fail(path, "'" + path + "' must be a number, got " + json_text(value));
  const double v = value.get<double>();
  if (!std::isfinite(v)) fail(path, "'" + path + "' must be finite");
  return v;
}

glm::dvec3 SceneFileReader::vec3(const json& value, const std::string& path) const {
  if (!value.is_array() || value.size() != 3) {
    fail(path, "'" + path + "' must be an array of 3 numbers, got " + json_text(value));
  }
  return {number(value[0], path + "[0]"), number(value[1], path + "[1]"), number(value[2], path + "[2]")};
}

bool SceneFileReader::boolean(const json& value, const std::string& path) const {
  if (!value.is_boolean()) fail(path, "'" + path + "' must be true or false, got " + json_text(value));
  return value.get<bool>();
}

void SceneFileReader::require_known_keys(const json& object, std::initializer_list<std::string_view> keys,
                                         const std::string& what, const std::string& path) const {
  for (const auto& item : object.items()) {
    bool known = false;
    for (std::string_view k : keys) known = known || k == item.key();
    if (known) continue;
    std::string list;
    for (std::string_view k : keys) list += std::string(list.empty() ? "" : ", ") + std::string(k);
    fail(path.empty() ? item.key() : path + "." + item.key(),
         "unknown key '" + shown(item.key()) + "' in " + what + " (known: " + list + ")");
  }
}

void SceneFileReader::require_known_object_keys(const json& object, std::initializer_list<std::string_view> keys,
                                                const std::string& what, const std::string& path) const {
  // What every object takes, whatever its kind: its colour and pattern,
  // and its material's keys (sol/material_kinds.h; read_object).
  static constexpr std::string_view kObjectKeys[] = {"color",     "pattern", "material", "emission",     "mirror",
                                                     "roughness", "ior",     "texture",  "texture_cells"};
  std::vector<std::string_view> all(keys);
  all.insert(all.end(), std::begin(kObjectKeys), std::end(kObjectKeys));
  for (const auto& item : object.items()) {
    if (std::find(all.begin(), all.end(), item.key()) != all.end()) continue;
    std::string list;
    for (std::string_view k : all) list += std::string(list.empty() ? "" : ", ") + std::string(k);
    fail(path.empty() ? item.key() : path + "." + item.key(),
         "unknown key '" + shown(item.key()) + "' in " + what + " (known: " + list + ")");
  }
}

void SceneFileReader::require_key(const json& object, const char* key, const std::string& what, const std::string& noun,
                                  const std::string& path) const {
  if (!object.contains(key)) fail(path, what + " needs " + noun);
}

// What the JSON parser is not asked to bear: nesting deeper than
// kSceneFileMaxDepth (it recurses per level) and NUL bytes (it would stop
// at one and ignore what follows). One pass, strings skipped.
void check_json_text(std::string_view text, std::string_view source) {
  int depth = 0, line = 1;
  std::size_t line_start = 0;
  bool in_string = false, escaped = false;
  auto fail = [&](std::size_t i, const std::string& what) {
    throw InvalidArgument(std::string(source) + ": " + what + " (line " + std::to_string(line) + ", column " +
                          std::to_string(i - line_start + 1) + ")");
  };
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\0') fail(i, "malformed JSON: a NUL byte");
    if (c == '\n') {
      ++line;
      line_start = i + 1;
    }
    if (in_string) {
      if (escaped) {
        escaped = false;
      } else if (c == '\\') {
        escaped = true;
      } else if (c == '"') {
        in_string = false;
      }
    } else if (c == '"') {
      in_string = true;
    } else if (c == '{' || c == '[') {
      if (++depth > kSceneFileMaxDepth) {
        fail(i, "nesting deeper than " + std::to_string(kSceneFileMaxDepth) + " levels of objects and arrays");
      }
    } else if (c == '}' || c == ']') {
      --depth;
    }
  }
}

std::string read_text_file(const std::string& path, const char* kind) {
  // What is not a regular file is refused before it is read: a directory
  // (not "malformed JSON"), a FIFO or a device (which could block or never
  // end), anything larger than any scene or path (sol::read_regular_file).
  constexpr std::uintmax_t kLargest = 64u << 20;
  FileRefusal why;
  std::optional<std::string> text = read_regular_file(path, kLargest, &why);
  if (text) return std::move(*text);
  switch (why.kind) {
    case FileRefusal::Kind::Directory: throw InvalidArgument(path + ": a directory, not a " + kind + " file");
    case FileRefusal::Kind::Missing: throw InvalidArgument(path + ": cannot open " + kind + " file (no such file)");
    case FileRefusal::Kind::TooLarge: throw InvalidArgument(path + ": larger than 64 MiB, more than any " + kind + " file");
    default: throw InvalidArgument(path + ": cannot read " + kind + " file: " + why.text);
  }
}

}  // namespace sol::detail
