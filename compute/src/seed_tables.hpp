// The connection solver's seed tables (sol::ConnectionTable: the
// minimisers', and the longer connections' for lights with a reach), built
// by libsol's solver when sol::vk is built (tools/seed_tables.cpp writes
// them as source) and compiled in: the kernels' exact balls and exact
// lights read them, and no program builds them at run time (about 0.3 s
// and 5 s of two cores). Each float as its bits.
#pragma once

#include <cstddef>
#include <cstdint>

#include "sol/connection.hpp"

namespace sol::vk::detail {

inline constexpr std::size_t kSeedTableWords = static_cast<std::size_t>(ConnectionTable::kCellsXY) *
                                               ConnectionTable::kCellsXY * ConnectionTable::kCellsZ *
                                               ConnectionTable::kSlots * 4;
extern const std::uint32_t kSeedsMinimisers[kSeedTableWords];
extern const std::uint32_t kSeedsLonger[kSeedTableWords];

}  // namespace sol::vk::detail
