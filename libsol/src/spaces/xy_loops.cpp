// The xy loops' quotient Sol/<γ1, γ2> (sol/spaces/xy_loops.hpp):
// "quotient": {"xy_loops": [[x1, y1], [x2, y2]]}.
#include "sol/spaces/xy_loops.hpp"

#include <string>

#include "../field_error.hpp"
#include "space_io.hpp"

namespace sol {

Lattice XYLoopsSpace::lattice() const { return Lattice::xy_loops(loops[0], loops[1]); }

namespace detail {

void read_quotient_space(const json& q, const SceneFileReader& r, XYLoopsSpace& space) {
  r.require_known_keys(q, {"xy_loops"}, "quotient (xy loops')", "quotient");
  const json& g = q["xy_loops"];
  if (!g.is_array() || g.size() != 2 || !g[0].is_array() || g[0].size() != 2 || !g[1].is_array() || g[1].size() != 2) {
    r.fail("quotient.xy_loops",
           "'quotient.xy_loops' must be two vectors [[x1, y1], [x2, y2]], got " + SceneFileReader::json_text(g));
  }
  for (int i = 0; i < 2; ++i) {
    const std::string at = "quotient.xy_loops[" + std::to_string(i) + "]";
    space.loops[static_cast<std::size_t>(i)] = {r.number(g[i][0], at + "[0]"), r.number(g[i][1], at + "[1]")};
  }
}

json write_quotient_space(const XYLoopsSpace& space) {
  const auto& g = space.loops;
  return {{"xy_loops", json::array({json::array({g[0].x, g[0].y}), json::array({g[1].x, g[1].y})})}};
}

void check_quotient_space(const XYLoopsSpace& space) { check_lattice(space, "quotient.xy_loops"); }

}  // namespace detail
}  // namespace sol
