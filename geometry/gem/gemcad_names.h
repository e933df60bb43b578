#pragma once
// The trade's names of a design's tiers (docs/gems.md "Tier names"): G the girdle, T the
// table, CU the culet, C1, C2, … the crown's rows and P1, P2, … the pavilion's, each side's
// rows by angle, the steepest (the row at the girdle) first.
#include <string>
#include <vector>

#include <refract/geometry/gem/gemcad.h>

namespace refract {

// One name per tier of the design, by its side and angle alone (tiers of one side and one
// angle, within 1e-9 degrees, share a name): |angle| 90 G, a crown tier of angle 0 T, a
// pavilion tier of angle 0 CU, the other crown tiers C1… and pavilion tiers P1… by angle,
// descending.
std::vector<std::string> trade_tier_names(const GemcadDesign& design);

// The tiers a trade name (G, T, CU, Ck, Pk) picks by trade_tier_names; empty for any other
// text or a name no tier has.
std::vector<std::size_t> tiers_of_trade_name(const GemcadDesign& design, const std::string& name);

}  // namespace refract
