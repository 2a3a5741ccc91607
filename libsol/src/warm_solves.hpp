// Warm starts for the exact solves of one march (libsol-internal).
//
// A march solves the same exact ball's distance at points a step apart,
// and asks for it again at the same point (its clearance, whether a pass
// ends, the normal at the hit). Within a WarmSolves scope on a thread,
// sol::distance and sol::minimising_geodesics answer a repeated target
// from the last answer, and start Newton from the last solution where the
// target moved little (kept only where it lands and is certified a
// minimiser, t <= T, as every other start; else the usual starts follow).
// The scope begins afresh, so a ray's solves depend on that ray alone:
// the image does not depend on which thread marched which rows.
#pragma once

namespace sol::detail {

class WarmSolves {
 public:
  WarmSolves();
  ~WarmSolves();
  WarmSolves(const WarmSolves&) = delete;
  WarmSolves& operator=(const WarmSolves&) = delete;

 private:
  bool m_outer;  // a scope was open already (nested: this one changes nothing)
};

}  // namespace sol::detail
