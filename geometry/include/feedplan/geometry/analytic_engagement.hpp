#pragma once
// Closed-form engagement for steady cuts: straight lines and arcs concentric with the previous pass
// (seed 003 Eq. 2, with the corrections of docs/method.md §5.1). Used as test oracles and as fast paths.
//
// r: tool radius; R_d: radial depth of cut; R: radius of the FINISHED WALL (not of the tool-centre
// path, which is R − r for an internal arc and R + r for an external one).

namespace feedplan::geometry {

//! Straight cut: cos α_en = 1 − R_d / r; R_d ≥ 2r is a full slot (α_en = π). Requires r > 0, R_d ≥ 0.
double straight_engagement_rad(double tool_radius_mm, double radial_depth_mm);

//! Internal (concave) arc: cos α_en = [(R − R_d)² − (R − r)² − r²] / [2 r (R − r)], clamped to [0, π].
//! Requires R > r > 0 and 0 ≤ R_d ≤ R.
double internal_arc_engagement_rad(double tool_radius_mm, double wall_radius_mm, double radial_depth_mm);

//! External (convex) arc: cos α_en = [(R + r)² + r² − (R + R_d)²] / [2 r (R + r)], clamped to [0, π].
//! Requires r > 0, R ≥ 0 and R_d ≥ 0.
double external_arc_engagement_rad(double tool_radius_mm, double wall_radius_mm, double radial_depth_mm);

//! Chip-thickness factor k = t_m / f_z = sin(min(α_en, π/2)) for an engagement that starts or ends at
//! the side of the tool (all three steady cases above).
double steady_chip_factor(double engagement_rad);

}  // namespace feedplan::geometry
