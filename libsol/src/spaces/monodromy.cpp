// A monodromy's torus bundle (sol/spaces/monodromy.hpp): "quotient":
// {"monodromy": [[a, b], [c, d]], "fibre_area": S}, the area optional.
#include "sol/spaces/monodromy.hpp"

#include <cmath>
#include <string>

#include "../field_error.hpp"
#include "space_io.hpp"

namespace sol {

Lattice MonodromySpace::lattice() const { return Lattice::from_monodromy(monodromy, fibre_area); }

namespace detail {

void read_quotient_space(const json& q, const SceneFileReader& r, MonodromySpace& space) {
  r.require_known_keys(q, {"monodromy", "fibre_area"}, "quotient (a monodromy's)", "quotient");
  const json& m = q["monodromy"];
  const std::string shape = "'quotient.monodromy' must be a 2 x 2 integer matrix [[a, b], [c, d]], got ";
  if (!m.is_array() || m.size() != 2 || !m[0].is_array() || m[0].size() != 2 || !m[1].is_array() || m[1].size() != 2) {
    r.fail("quotient.monodromy", shape + SceneFileReader::json_text(m));
  }
  long long entries[2][2] = {};
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) {
      const std::string at = "quotient.monodromy[" + std::to_string(i) + "][" + std::to_string(j) + "]";
      const double v = r.number(m[i][j], at);
      if (!(std::abs(v) <= 2147483648.0) || v != std::floor(v)) {
        r.fail(at, "'" + at + "' must be an integer within ±2^31, got " + SceneFileReader::json_text(m[i][j]));
      }
      entries[i][j] = static_cast<long long>(v);
    }
  }
  space.monodromy = {entries[0][0], entries[0][1], entries[1][0], entries[1][1]};
  if (q.contains("fibre_area")) space.fibre_area = r.number(q["fibre_area"], "quotient.fibre_area");
}

json write_quotient_space(const MonodromySpace& space) {
  const Monodromy& m = space.monodromy;
  json q = {{"monodromy", json::array({json::array({m.a, m.b}), json::array({m.c, m.d})})}};
  if (space.fibre_area) q["fibre_area"] = *space.fibre_area;
  return q;
}

void check_quotient_space(const MonodromySpace& space) {
  // (A bad area is named as the area; anything else as the matrix.)
  const bool area = space.fibre_area && !(*space.fibre_area >= 0.01 && *space.fibre_area <= 10000.0);
  check_lattice(space, area ? "quotient.fibre_area" : "quotient.monodromy");
}

}  // namespace detail
}  // namespace sol
