// The connection solver's seed tables (sol::ConnectionTable: the
// minimisers', and the longer connections' for lights with a reach), built
// by libsol's solver when sol::vk is built (tools/seed_tables.cpp writes
// them as source) and compiled in: the kernels' exact balls and exact
// lights read them, and no program builds them at run time (about 0.3 s
// and 5 s of two cores). Each float written exactly (a hexadecimal literal).
#pragma once

#include <cstddef>

#include "sol/connection.hpp"

namespace sol::vk::detail {

inline constexpr std::size_t kSeedTableFloats = static_cast<std::size_t>(ConnectionTable::kCellsXY) *
                                               ConnectionTable::kCellsXY * ConnectionTable::kCellsZ *
                                               ConnectionTable::kSlots * 4;
extern const float kSeedsMinimisers[kSeedTableFloats];
extern const float kSeedsLonger[kSeedTableFloats];

}  // namespace sol::vk::detail
