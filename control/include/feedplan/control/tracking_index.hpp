#pragma once
// Seed 004's tracking performance index (Rubio & De la Sen 2007, §IV, Eq. 10), by which its supervisor
// ranks the discrete models:
//
//   J_k^(l) = Σ_{j=k−M}^{k} λ^{k−j} ∫_{(j−1)T}^{jT} |F_r,l(τ) − F_p,l(τ)| dτ,
//
// λ ∈ (0, 1] a forgetting factor, M > 0 the window in periods. Each period's integral is taken here by the
// trapezoid rule on the m + 1 equally spaced instants HeldSystemSimulator gives (exact values there); the
// rule's error is O((T/m)²) per period where the difference is smooth, larger only where it changes sign.

#include <span>

namespace feedplan::control {

//! ∫ |a(t) − b(t)| dt over one period `period_s` from the values of a and b at m + 1 equally spaced
//! instants (same count, ≥ 2; asserted), trapezoid rule. In the signals' unit times s (N·s for forces).
double period_absolute_area(std::span<const double> a, std::span<const double> b, double period_s);

//! Σ_i λ^i area_i: Eq. 10 for the period areas `areas_newest_first` (the caller holds the window, M + 1
//! periods) and the forgetting factor λ (in (0, 1], asserted).
double tracking_index(std::span<const double> areas_newest_first, double forgetting_factor);

}  // namespace feedplan::control
