// The spaces the rays live in: Sol itself or a quotient Γ\Sol of one of the
// kinds listed once in SOL_QUOTIENT_SPACES. Each quotient is a struct of its
// parameters in sol/spaces/<space>.hpp whose lattice() gives the
// sol::Lattice that the march (teleport, contains), the images
// (words_near_domain) and the observer take; its scene-file form and checks
// are in libsol/src/spaces/<space>.cpp. A world holds one (World::space).
#pragma once

#include <optional>
#include <cstddef>
#include <type_traits>
#include <variant>

#include "sol/lattice.hpp"
#include "sol/spaces/golden.hpp"
#include "sol/spaces/monodromy.hpp"
#include "sol/spaces/xy_loops.hpp"
#include "sol/spaces/z_loop.hpp"

namespace sol {

/// The quotients, one line each: X(struct, Quotient value, scene-file key,
/// form). The key names the space in "quotient": the string itself for a
/// space without parameters ("golden"), else the key of the object that
/// holds them ({"monodromy": ...}); the form is what error messages show.
#define SOL_QUOTIENT_SPACES(X)                                             \
  X(GoldenSpace, Golden, "golden", "golden")                               \
  X(MonodromySpace, Monodromy, "monodromy", "{\"monodromy\": [[a, b], [c, d]]}") \
  X(ZLoopSpace, ZLoop, "z_loop", "{\"z_loop\": h}")                        \
  X(XYLoopsSpace, XYLoops, "xy_loops", "{\"xy_loops\": [[x1, y1], [x2, y2]]}")

/// Sol itself: no lattice. Scene file: "quotient": "none".
struct SolSpace {
  bool operator==(const SolSpace&) const = default;
};

#define SOL_QUOTIENT_VALUE(type, value, key, form) , value
/// Which space: Sol (None) or a quotient, in the order of the list.
enum class Quotient { None SOL_QUOTIENT_SPACES(SOL_QUOTIENT_VALUE) };
#undef SOL_QUOTIENT_VALUE

#define SOL_QUOTIENT_TYPE(type, value, key, form) , type
/// A space and its parameters; Space's index is its Quotient value.
using Space = std::variant<SolSpace SOL_QUOTIENT_SPACES(SOL_QUOTIENT_TYPE)>;
#undef SOL_QUOTIENT_TYPE

#define SOL_QUOTIENT_CHECK(type, value, key, form) \
  static_assert(std::is_same_v<std::variant_alternative_t<static_cast<std::size_t>(Quotient::value), Space>, type>);
SOL_QUOTIENT_SPACES(SOL_QUOTIENT_CHECK)
#undef SOL_QUOTIENT_CHECK

/// Which space `space` is.
inline Quotient quotient_of(const Space& space) { return static_cast<Quotient>(space.index()); }

/// The space's lattice, none in Sol; throws the InvalidArgument of a bad
/// parameter (a monodromy that is not hyperbolic, ...).
std::optional<Lattice> lattice_of(const Space& space);

/// The space of `quotient` with its default parameters (MonodromySpace:
/// the golden monodromy without a fibre area).
Space default_space(Quotient quotient);

}  // namespace sol
