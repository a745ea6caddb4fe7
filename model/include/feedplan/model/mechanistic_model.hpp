#pragma once
// The mechanistic force model (Altintas, Manufacturing Automation, ch. 2; docs/method.md §6.1): per unit
// length of cutting edge, a tooth element cutting a chip h feels
//   dF_t = (K_tc·s(h)·h + K_te) dz,  dF_r = (K_rc·s(h)·h + K_re) dz,  dF_a = (K_ac·s(h)·h + K_ae) dz,
// with the size effect s(h) = (max(h, h_min) / h_ref)^(−m) (s ≡ 1 when m = 0; k_c = k_1·h^(−m),
// docs/method.md §6.2), and each tooth j of the cutter offset radially by its runout r_j.
// The force kernel on engaged arcs is in mechanistic_force.hpp.

#include <optional>
#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"

namespace feedplan::model {

//! Cutting and edge coefficients of a tool–material pair, with an optional size effect and the
//! tool's radial runout.
struct MechanisticModel {
  double ktc_n_per_mm2 = 0.0;  //!< tangential cutting coefficient K_tc, N/mm²
  double krc_n_per_mm2 = 0.0;  //!< radial cutting coefficient K_rc, N/mm²
  double kac_n_per_mm2 = 0.0;  //!< axial cutting coefficient K_ac, N/mm²
  double kte_n_per_mm = 0.0;   //!< tangential edge coefficient K_te, N/mm
  double kre_n_per_mm = 0.0;   //!< radial edge coefficient K_re, N/mm
  double kae_n_per_mm = 0.0;   //!< axial edge coefficient K_ae, N/mm
  //! Size-effect exponent m, in [0, 1): the cutting coefficients hold at h_ref and scale as
  //! (h / h_ref)^(−m). 0 turns the size effect off.
  double size_exponent = 0.0;
  double size_reference_chip_mm = 0.1;  //!< h_ref: chip thickness at which K_tc, K_rc, K_ac hold, mm (> 0)
  //! h_min: smallest chip the size effect is evaluated at, keeping h^(−m) finite, mm (> 0)
  double size_min_chip_mm = 0.005;
  //! Radial runout of each tooth, mm: tooth j cuts at radius r + runout_mm[j] (teeth numbered in the
  //! order they pass a point, see mechanistic_force.hpp). Empty: none; else one value per flute.
  std::vector<double> runout_mm;
  //! The flutes' helix angle the cutting tests showed, deg, in (−90, 90): the kernel uses it instead of the
  //! cutter's catalogue helix (a tool's helix is a nominal value; the pulse of each tooth shows the real
  //! one). Empty: the cutter's.
  std::optional<double> helix_deg;
};

//! Every problem with the model's numbers, each named "<field_prefix><field>" with its value and what
//! was expected ("mechanistic.ktc_n_per_mm2 = nan: must be finite"): finite coefficients; a size
//! exponent in [0, 1); a reference and a smallest chip finite and > 0; finite runouts; a helix, when
//! given, in (−90, 90). Empty when the
//! model is usable. How many runouts a cutter needs is checked with the cutter (mechanistic_force.hpp).
std::vector<InputProblem> validate(const MechanisticModel& model, const std::string& field_prefix = "mechanistic.");

}  // namespace feedplan::model
