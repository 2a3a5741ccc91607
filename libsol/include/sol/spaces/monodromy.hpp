// The torus bundle of a hyperbolic monodromy A: the compact quotient of
// Lattice::from_monodromy. Scene file: "quotient": {"monodromy": [[a, b],
// [c, d]], "fibre_area": S} (the area optional).
#pragma once

#include <optional>

#include "sol/lattice.hpp"

namespace sol {

struct MonodromySpace {
  /// A in SL(2, Z), |trace| > 2 (a negative trace turns the fibre:
  /// Lattice::turns). [[2, 1], [1, 1]] without a fibre area is the golden
  /// lattice.
  Monodromy monodromy{};
  /// The area of the fibre torus, in [0.01, 10000] (none: the normalisation
  /// of Lattice::from_monodromy).
  std::optional<double> fibre_area;

  /// Lattice::from_monodromy(monodromy, fibre_area); throws its InvalidArgument.
  Lattice lattice() const;
  bool operator==(const MonodromySpace&) const = default;
};

}  // namespace sol
