// The golden quotient (sol/spaces/golden.hpp): "quotient": "golden".
#include "sol/spaces/golden.hpp"

#include "space_io.hpp"

namespace sol {

Lattice GoldenSpace::lattice() const { return Lattice::golden(); }

namespace detail {

void read_quotient_space(const json&, const SceneFileReader&, GoldenSpace&) {}

json write_quotient_space(const GoldenSpace&) { return "golden"; }

void check_quotient_space(const GoldenSpace&) {}

}  // namespace detail
}  // namespace sol
