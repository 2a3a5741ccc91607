// The non-compact quotient Sol/<γ3> of the loop γ3 = (0, 0, h) alone, the
// domain R² × [0, h) (Lattice::z_loop). Scene file: "quotient": {"z_loop": h}.
#pragma once

#include "sol/lattice.hpp"

namespace sol {

struct ZLoopSpace {
  /// The loop's height h, in [1, 20].
  double height = 1.0;

  /// Lattice::z_loop(height); throws its InvalidArgument.
  Lattice lattice() const;
  bool operator==(const ZLoopSpace&) const = default;
};

}  // namespace sol
