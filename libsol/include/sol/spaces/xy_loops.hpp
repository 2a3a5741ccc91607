// The non-compact quotient Sol/<γ1, γ2> of the loops γ1 = (x1, y1, 0) and
// γ2 = (x2, y2, 0) alone, a torus times a line (Lattice::xy_loops). Scene
// file: "quotient": {"xy_loops": [[x1, y1], [x2, y2]]}.
#pragma once

#include <array>

#include <glm/vec2.hpp>

#include "sol/lattice.hpp"

namespace sol {

struct XYLoopsSpace {
  /// γ1's and γ2's (x, y): independent.
  std::array<glm::dvec2, 2> loops{glm::dvec2(1.0, 0.0), glm::dvec2(0.0, 1.0)};

  /// Lattice::xy_loops(loops[0], loops[1]); throws its InvalidArgument.
  Lattice lattice() const;
  bool operator==(const XYLoopsSpace&) const = default;
};

}  // namespace sol
