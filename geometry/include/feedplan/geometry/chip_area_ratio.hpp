#pragma once
// How far an engagement is from the straight cuts a response surface is fitted on (docs/method.md §5.3).
//
// The force model F̂(t_m, L) knows t_m and L only. In a straight cut (and on steady arcs) the engaged
// arc ends at the side of the tool, so the chip thins from t_m to 0 along it; where the tool enters
// material the arc lies at the front and the chip is close to t_m all along it. For the same (t_m, L)
// such an engagement cuts more chip — up to twice as much — and the straight-cut model under-predicts
// it (the entry overshoots of issues 5 and 6).
//
// ρ = A / A_straight: the uncut chip area over the engaged intervals, A = f_z ∫ max(sin φ, 0) dφ, over
// that of the straight cut with the same t_m and L (arc [π − α, π], α = L / r, at the feed per tooth
// f_z' = t_m / sin(min(α, π/2))): A_straight = f_z' (1 − cos(min(α, π))). So
// ρ = ∫ max(sin φ, 0) dφ · sin(min(α, π/2)) / (k (1 − cos(min(α, π)))) with k = t_m / f_z the chip factor.
// ρ = 1 on every straight cut and steady arc (up or down milling, any immersion, slots); a centred
// front arc of width α ≤ π/2 has ρ = 2 cos(α/2).

#include "feedplan/geometry/engagement.hpp"

namespace feedplan::geometry {

//! k = t_m / f_z of the engaged intervals [begin, end): the largest sin φ over them (h = f_z sin φ), 0 when
//! no tooth point cuts a chip (EngagementSample::chip_factor on moves with XY motion).
double chip_factor(const EngagedInterval* begin, const EngagedInterval* end);

//! ρ (see the file comment) for the engaged intervals [begin, end) (immersion angles, rad), never below
//! 1; 1 when nothing is engaged or no chip is cut.
double chip_area_ratio(const EngagedInterval* begin, const EngagedInterval* end);

}  // namespace feedplan::geometry
