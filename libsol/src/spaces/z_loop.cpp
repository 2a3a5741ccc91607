// The z loop's quotient Sol/<(0, 0, h)> (sol/spaces/z_loop.hpp):
// "quotient": {"z_loop": h}.
#include "sol/spaces/z_loop.hpp"

#include <string>

#include "../field_error.hpp"
#include "space_io.hpp"

namespace sol {

Lattice ZLoopSpace::lattice() const { return Lattice::z_loop(height); }

namespace detail {

void read_quotient_space(const json& q, const SceneFileReader& r, ZLoopSpace& space) {
  r.require_known_keys(q, {"z_loop"}, "quotient (a z loop's)", "quotient");
  space.height = r.number(q["z_loop"], "quotient.z_loop");
}

json write_quotient_space(const ZLoopSpace& space) { return {{"z_loop", space.height}}; }

void check_quotient_space(const ZLoopSpace& space) { check_lattice(space, "quotient.z_loop"); }

}  // namespace detail
}  // namespace sol
