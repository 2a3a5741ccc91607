// The dispatch over SOL_QUOTIENT_SPACES (sol/spaces.hpp): a space's
// lattice, its defaults, and the scene file's "quotient" read, written and
// checked by the space's own functions (space_io.hpp).
#include <string>
#include <vector>
#include <type_traits>

#include "../field_error.hpp"
#include "space_io.hpp"
#include "sol/spaces.hpp"

namespace sol {

std::optional<Lattice> lattice_of(const Space& space) {
  return std::visit(
      [](const auto& s) -> std::optional<Lattice> {
        if constexpr (std::is_same_v<std::decay_t<decltype(s)>, SolSpace>) {
          return std::nullopt;
        } else {
          return s.lattice();
        }
      },
      space);
}

Space default_space(Quotient quotient) {
  switch (quotient) {
    case Quotient::None:
      return SolSpace{};
#define SOL_QUOTIENT_DEFAULT(type, value, key, form) \
  case Quotient::value:                              \
    return type{};
      SOL_QUOTIENT_SPACES(SOL_QUOTIENT_DEFAULT)
#undef SOL_QUOTIENT_DEFAULT
  }
  return SolSpace{};
}

namespace detail {
namespace {

// "'quotient' must be none, golden, {...} or {...}, got ".
std::string quotient_forms() {
  std::vector<std::string> forms{"none"};
#define SOL_QUOTIENT_FORM(type, value, key, form) forms.emplace_back(form);
  SOL_QUOTIENT_SPACES(SOL_QUOTIENT_FORM)
#undef SOL_QUOTIENT_FORM
  std::string text = "'quotient' must be ";
  for (std::size_t i = 0; i < forms.size(); ++i) {
    text += (i == 0 ? "" : i + 1 == forms.size() ? " or " : ", ") + forms[i];
  }
  return text + ", got ";
}

// Whether the space is named by a string alone (no parameters).
constexpr bool named_by_string(std::string_view key, std::string_view form) { return key == form; }

}  // namespace

Space read_space(const json& q, const SceneFileReader& r) {
  if (q.is_string()) {
    const std::string& name = q.get_ref<const std::string&>();
    if (name == "none") return SolSpace{};
#define SOL_QUOTIENT_NAMED(type, value, key, form)    \
  if (named_by_string(key, form) && name == key) {    \
    type space;                                       \
    read_quotient_space(q, r, space);                 \
    return space;                                     \
  }
    SOL_QUOTIENT_SPACES(SOL_QUOTIENT_NAMED)
#undef SOL_QUOTIENT_NAMED
  }
  if (!q.is_object()) r.fail("quotient", quotient_forms() + SceneFileReader::json_text(q));
  int named = 0;
  std::string keys;
#define SOL_QUOTIENT_COUNT(type, value, key, form)                 \
  if (!named_by_string(key, form)) {                               \
    named += static_cast<int>(q.contains(key));                    \
    keys += std::string(keys.empty() ? "'" : ", '") + key + "'";   \
  }
  SOL_QUOTIENT_SPACES(SOL_QUOTIENT_COUNT)
#undef SOL_QUOTIENT_COUNT
  if (named > 1) r.fail("quotient", quotient_forms() + SceneFileReader::json_text(q) + " (one of the keys, not several)");
  if (named == 0) r.fail("quotient", "'quotient' needs one of the keys " + keys + ", got " + SceneFileReader::json_text(q));
#define SOL_QUOTIENT_KEYED(type, value, key, form)      \
  if (!named_by_string(key, form) && q.contains(key)) { \
    type space;                                         \
    read_quotient_space(q, r, space);                   \
    return space;                                       \
  }
  SOL_QUOTIENT_SPACES(SOL_QUOTIENT_KEYED)
#undef SOL_QUOTIENT_KEYED
  return SolSpace{};
}

json write_space(const Space& space) {
  return std::visit(
      [](const auto& s) -> json {
        if constexpr (std::is_same_v<std::decay_t<decltype(s)>, SolSpace>) {
          return "none";
        } else {
          return write_quotient_space(s);
        }
      },
      space);
}

void check_space(const Space& space) {
  std::visit(
      [](const auto& s) {
        if constexpr (!std::is_same_v<std::decay_t<decltype(s)>, SolSpace>) check_quotient_space(s);
      },
      space);
}

}  // namespace detail
}  // namespace sol
