// What each quotient space supplies to the scene model besides its
// lattice (not installed): its scene-file form and the checks of its
// parameters, in libsol/src/spaces/<space>.cpp. The scene file's
// "quotient" (read_space, write_space in spaces.cpp) and sol::validate
// (check_space) dispatch over SOL_QUOTIENT_SPACES.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

#include "../field_error.hpp"
#include "../scene_reader.hpp"
#include "sol/spaces.hpp"

namespace sol::detail {

using nlohmann::json;

#define SOL_QUOTIENT_IO(type, value, key, form)                                                              \
  /* Reads `q`, the value of "quotient" (a string for a space without parameters, else an object */ \
  /* holding its key), into `space`; fails through `r` naming the field ("quotient.z_loop"). */      \
  void read_quotient_space(const json& q, const SceneFileReader& r, type& space);                     \
  /* The value of "quotient" that read_quotient_space reads back. */                                  \
  json write_quotient_space(const type& space);                                                        \
  /* Throws a FieldError naming the field ("quotient.fibre_area") where the lattice cannot be made. */ \
  void check_quotient_space(const type& space);
SOL_QUOTIENT_SPACES(SOL_QUOTIENT_IO)
#undef SOL_QUOTIENT_IO

/// The space's lattice made once to check its parameters: a bad one a
/// FieldError at `at` ("quotient.z_loop") with the lattice's reason.
template <class S>
void check_lattice(const S& space, const std::string& at) {
  try {
    (void)space.lattice();
  } catch (const InvalidArgument& e) {
    field_error(at, at + ": " + e.what());
  }
}

/// "quotient"'s value into a space: "none", a space's key as a string, or an
/// object with exactly one space's key.
Space read_space(const json& q, const SceneFileReader& r);
/// The value of "quotient" for `space`.
json write_space(const Space& space);
/// Every parameter of the space; a FieldError naming the field.
void check_space(const Space& space);

}  // namespace sol::detail
