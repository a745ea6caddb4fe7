#pragma once
// Mechanistic cutting coefficients of a tool–material pair (Altintas, Manufacturing Automation, ch. 2;
// docs/method.md §6.1): per unit chip width, dF_t = (Ktc h + Kte) dz, dF_r = (Krc h + Kre) dz,
// dF_a = (Kac h + Kae) dz, with an optional size effect on the cutting terms.

#include <initializer_list>

namespace feedplan::sim {

//! Cutting (shear) and edge (ploughing) coefficients, with an optional Kienzle-type size effect.
struct CuttingCoefficients {
  double ktc_n_per_mm2 = 0.0;  //!< tangential cutting coefficient
  double krc_n_per_mm2 = 0.0;  //!< radial cutting coefficient
  double kac_n_per_mm2 = 0.0;  //!< axial cutting coefficient
  double kte_n_per_mm = 0.0;   //!< tangential edge coefficient
  double kre_n_per_mm = 0.0;   //!< radial edge coefficient
  double kae_n_per_mm = 0.0;   //!< axial edge coefficient
  //! Size-effect exponent m_c: the cutting coefficients scale as (h / size_reference_chip_mm)^(−m_c)
  //! (k_c = k_1 h^(−m_c), docs/method.md §6.2). 0 turns the size effect off.
  double size_exponent = 0.0;
  double size_reference_chip_mm = 0.1;  //!< chip thickness at which the K*c values above hold, mm
  //! Smallest chip thickness the size effect is evaluated at (keeps h^(−m_c) finite), mm.
  double size_min_chip_mm = 0.005;
};

//! `coefficients` with all six force coefficients (cutting and edge) × `factor`: a material whose
//! forces are `factor` times as large at every chip (the size effect unchanged).
inline CuttingCoefficients scaled(CuttingCoefficients coefficients, double factor) {
  for (double* k : {&coefficients.ktc_n_per_mm2, &coefficients.krc_n_per_mm2, &coefficients.kac_n_per_mm2,
                    &coefficients.kte_n_per_mm, &coefficients.kre_n_per_mm, &coefficients.kae_n_per_mm}) {
    *k *= factor;
  }
  return coefficients;
}

}  // namespace feedplan::sim
