// The golden quotient Γ\Sol: the torus bundle of the monodromy [[2, 1],
// [1, 1]] in Lattice::golden()'s normalisation. Scene file: "quotient":
// "golden".
#pragma once

#include "sol/lattice.hpp"

namespace sol {

struct GoldenSpace {
  /// Lattice::golden().
  Lattice lattice() const;
  bool operator==(const GoldenSpace&) const = default;
};

}  // namespace sol
