#pragma once
// Seed 004's two ways of choosing the hold's correcting gain β from the models' tracking indices
// (Rubio & De la Sen 2007, §III.E–F; tracking_index.hpp):
//
// Scheme 1 (§III.E), a fixed set {β⁽¹⁾, …, β⁽ⁿᵐ⁾}: the model of smallest index is used (§V: β⁽ⁱ⁾ =
// 1 − (i − 1)/10, i = 1 … 15).
//
// Scheme 2 (§III.F), a neighbour search: besides the active β_k only β_k ± Δβ are simulated. When the
// residence time allows a comparison, the smallest index wins, and
//   - if β stays, Δβ ← Δβ / m (m > 1) and the neighbours are β ± Δβ;
//   - if β moves to a neighbour, Δβ is kept and the neighbours are the new β ± Δβ.
// Seed 004 prints, for a move down, β^inf_{k+1} = β_k − Δβ — the new active value itself; read here as
// the misprint of the move up's mirror image, β_{k+1} − Δβ. Neighbours are kept inside [−1, 1] (the range
// of the hold); a clamped neighbour may coincide with β and then never wins (ties keep β). §V: Δβ = 0.2,
// m = 2 at the start; the starting β is "arbitrary".

#include <array>
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"

namespace feedplan::control {

//! Which of §III's schemes picks β.
enum class SwitchingScheme {
  kFixedSet,         //!< scheme 1: the smallest index among a fixed bank of β
  kNeighbourSearch,  //!< scheme 2: β or one of β ± Δβ, Δβ shrinking while β stays
};

//! Seed 004 §V's bank for scheme 1: β⁽ⁱ⁾ = 1 − (i − 1)/10, i = 1 … 15 (1, 0.9, …, −0.4).
std::vector<double> seed_004_beta_bank();

//! Scheme 1: the position of the smallest of `indices` (not empty, asserted); a tie keeps `active`, then
//! the lowest position. NaN never wins.
std::size_t fixed_set_choice(std::span<const double> indices, std::size_t active);

//! Scheme 2's settings.
struct NeighbourSearchParameters {
  //! β at the start, in [−1, 1]. Seed 004 calls it arbitrary; 1 (the first-order hold, the first of scheme
  //! 1's bank) is a choice made here.
  double initial_beta = 1.0;
  double initial_step = 0.2;  //!< Δβ at the start, in (0, 2]; seed 004 §V: 0.2
  double step_divisor = 2.0;  //!< m, > 1; seed 004 §V: 2
};

//! Every problem with the settings, each named "<field_prefix><field>" with its value and the rule
//! ("neighbour_search.step_divisor = 1: must be finite and > 1"). Empty when usable.
std::vector<InputProblem> validate(const NeighbourSearchParameters& parameters,
                                   const std::string& field_prefix = "neighbour_search.");

//! Scheme 2's state.
class NeighbourBetaSearch {
 public:
  //! Needs parameters that pass validate() (asserted).
  explicit NeighbourBetaSearch(const NeighbourSearchParameters& parameters);

  //! β − Δβ, β, β + Δβ, each clamped to [−1, 1].
  std::array<double, 3> candidates() const;

  //! One comparison: the candidate of smallest index (in candidates()' order; ties keep β, NaN never wins)
  //! becomes β and Δβ is updated as the file comment says. Returns whether β changed.
  bool update(const std::array<double, 3>& indices);

  double active_beta() const { return beta_; }  //!< β now
  double step() const { return step_; }          //!< Δβ now

 private:
  double beta_ = 0.0;
  double step_ = 0.0;
  double divisor_ = 2.0;
};

}  // namespace feedplan::control
