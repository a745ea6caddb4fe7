#pragma once
// Which kind of the chosen model plans: the response surface F̂(t_m, L) or the mechanistic model of the same
// tool and material (cutting and edge coefficients), with the reason in words.
//
// --model-kind decides when given. Otherwise the mechanistic kind plans when the pair has one and either
//   - the path leaves the response surface's fitted contact lengths at more than
//     kExtrapolatedShareForMechanistic of its engaged samples (a slot, a plunge into a corner: a quadratic in
//     (t_m, L) has nothing to say there, while the cutting mechanics hold at any engagement), or
//   - it predicted the engagements it was not fitted on better (the lower leave-one-engagement-out error on
//     the pair's own cutting tests, model_db/engagement_groups.hpp).
// A mechanistic version identified on another cutter (the chosen model is borrowed, or its runout has a value
// per flute of another flute count) keeps its cutting and edge coefficients and size effect — properties of
// the tool material and workpiece — and drops the tested cutter's runout and helix: the plan uses this
// cutter's catalogue helix and no runout.

#include <optional>
#include <string>

#include "feedplan/geometry/engagement.hpp"
#include "feedplan/geometry/tool.hpp"
#include "feedplan/model/response_surface_model.hpp"
#include "feedplan/model_db/store.hpp"
#include "feedplan/model_db/store_records.hpp"
#include "model_choice.hpp"

namespace feedplan::cli {

//! Share of engaged samples outside the response surface's fitted contact lengths above which the
//! mechanistic kind plans (when the pair has one and no kind is asked for).
inline constexpr double kExtrapolatedShareForMechanistic = 0.02;

//! How far a mechanistic model identified on another cutter of the same tool material can be off, as a
//! fraction of its force: the cutter's geometry (diameter, flutes, helix) is modelled, its edge radius and rake
//! are not (they change K_te and K_tc by about this much between end mills of one grade).
inline constexpr double kOtherCutterRelative = 0.1;

//! The mechanistic version that plans (nothing: the response surface), why, and how far the kind that
//! plans is borrowed.
struct ModelKindChoice {
  std::optional<model_db::ModelRecord> mechanistic;
  std::string reason;
  //! δ of the kind that plans: the chosen model's (model_borrowing.hpp) for the response surface; for the
  //! mechanistic kind its material differences plus kOtherCutterRelative when the cutter differs (diameter,
  //! flutes and helix are in its kernel, so they do not count again).
  double borrowed_fraction = 0.0;
  //! The largest chip the mechanistic kind may plan (PlanOptions::max_chip_thickness_mm), mm: the largest the
  //! pair's cutting tests saw (the response surface's fitted range), scaled by this cutter's diameter over the
  //! tested one's (feeds per tooth are chosen in proportion to the diameter). 0 for the response surface, which
  //! holds its range itself.
  double max_chip_thickness_mm = 0.0;
};

//! The relative uncertainty r the plan holds F̂ + z·σ at the target with: `requested` (--cautious) when
//! given, else the choice's borrowed_fraction / kBorrowedModelSigmas.
double planning_uncertainty(const ModelKindChoice& kind, std::optional<double> requested);

//! Share of the engaged samples of `engagement` whose contact length lies outside the fitted range of
//! `surface` by more than 5 % of the range's ends.
double extrapolated_contact_share(const model::ResponseSurfaceModel& surface, const geometry::EngagementProfile& engagement);

//! The kind for `chosen` (a response-surface version) planning `tool`: `requested` is "", "mechanistic" or
//! "response-surface" (else InputError on --model-kind); `extrapolated_share` is extrapolated_contact_share of
//! the path to be planned, when known. Throws InputError for "mechanistic" when the pair has none.
ModelKindChoice choose_model_kind(const model_db::Store& store, const ChosenModel& chosen, const geometry::Tool& tool,
                                  const std::string& requested, std::optional<double> extrapolated_share);

}  // namespace feedplan::cli
