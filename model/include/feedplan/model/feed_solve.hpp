#pragma once
// The feed per tooth that makes the response-surface model predict a target force (seed 003 §2.2,
// docs/method.md §5.3).
//
// The geometry fixes the chip factor k = t_m / f_z = sin(min(α_en, π/2)) and the contact length L at a
// path sample; the feed does not change them. With t_m = k f, F̂ is a quadratic in f:
//
//   F̂(f) = A + B X1 + C X1²,  X1 = (k f − c1) / s1,
//   A = β0 + β2 X2 + β22 X2²,  B = β1 + β12 X2,  C = β11,  X2 = (L − c2) / s2.
//
// dF̂/df = (k / s1)(B + 2 C X1), so F̂ rises with the feed where B + 2 C X1 > 0. A quadratic has at most
// one root on its rising branch: with D = B² − 4 C (A − F_target) ≥ 0 it is X1 = (−B + √D) / (2C), where
// dF̂/dX1 = +√D (for C > 0 the larger root, for C < 0 the smaller one; computed in the cancellation-free
// form −2 (A − F_target) / (B + √D) when B ≥ 0). β11 = 0 is the linear case: X1 = (F_target − A) / B when
// B > 0, no rising root when B ≤ 0; the same formula covers it, so a tiny β11 needs no special tolerance.
// "The smallest positive root on the rising branch" is that root when it lies at f > 0. The fitted t_m
// range [t_min, t_max] (with the relative tolerance kRangeRelativeTolerance) then decides the status:
//
//   rising root at f > 0, t_min ≤ k f ≤ t_max     → kOk: that feed, F̂ = F_target
//   rising root at f > 0, k f > t_max             → kClampedToRange: f = t_max / k, F̂ < F_target there
//   rising root at f > 0, k f < t_min             → kClampedToRange: f = t_min / k (F̂ ≥ F_target there
//                                                   for a model rising over the range)
//   no rising root at f > 0, F̂(t_m = 0) ≥ F_target → kTargetBelowModel: f = t_min / k, the smallest feed
//                                                   in range (the model sits above the target as f → 0+)
//   no rising root at f > 0, F̂(t_m = 0) < F_target → kUnreachable: the feed where F̂ is largest over
//                                                   [t_min, t_max] (the vertex −B/(2C) when C < 0 and it
//                                                   lies in range, else the better range edge; on a tie the
//                                                   smaller feed)
//
// Every status returns a usable feed and the force the model predicts there; only kOk meets the target.
// The result also says when L lies outside the fitted L range (the model extrapolates in L).

#include <optional>
#include <string>

#include "feedplan/model/response_surface_model.hpp"

namespace feedplan::model {

//! How the feed relates to the target force (see the file comment for the exact rule).
enum class FeedSolveStatus {
  kOk,                //!< F̂ = target on the rising branch, inside the fitted t_m range
  kClampedToRange,    //!< the rising-branch solution lies outside the fitted t_m range; the feed is at its edge
  kTargetBelowModel,  //!< F̂ exceeds the target already as f → 0+; the feed is the smallest in range
  kUnreachable,       //!< F̂ never reaches the target on its rising branch; the feed is at F̂'s range maximum
};

//! "ok", "clamped to range", "target below model", "unreachable".
std::string to_string(FeedSolveStatus status);

//! The feed per tooth for one path sample.
struct FeedSolution {
  FeedSolveStatus status = FeedSolveStatus::kOk;  //!< how the feed relates to the target
  double feed_per_tooth_mm = 0.0;   //!< feed per tooth at the tool centre to use, mm/tooth (0 only if t_min = 0)
  double chip_mm = 0.0;             //!< t_m = k · feed_per_tooth_mm, mm
  double predicted_force_n = 0.0;   //!< F̂ at that feed and L, N (the target, up to rounding, when kOk)
  //! The rising-branch root when it lies at a positive feed, mm/tooth: equal to feed_per_tooth_mm for
  //! kOk, the unclamped solution for kClampedToRange, empty otherwise.
  std::optional<double> root_feed_per_tooth_mm;
  bool contact_length_outside = false;  //!< L lies outside the fitted L range: F̂ is extrapolated in L
  //! Empty for kOk inside the fitted L range; else one sentence saying what happened, with the numbers.
  std::string message;
};

//! The feed per tooth f at which the model predicts target_force_n for chip factor k = chip_factor
//! (t_m = k f) and contact length contact_length_mm, by the rule of the file comment. Needs a model that
//! passes validate(), k in (0, 1], a finite L ≥ 0 and a finite target > 0.
//!
//! Returns the feed, the predicted force there, the status and, for anything but kOk inside the L range,
//! a message. Throws feedplan::InputError listing every problem with the arguments (fields "chip_factor",
//! "contact_length_mm", "target_force_n") and the model (validate()'s "model.…" fields).
FeedSolution solve_feed(const ResponseSurfaceModel& model, double chip_factor, double contact_length_mm,
                        double target_force_n);

}  // namespace feedplan::model
