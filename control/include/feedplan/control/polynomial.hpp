#pragma once
// A polynomial in z with real coefficients, highest power first: the form in which seed 004 (Rubio & De la
// Sen 2007) writes its discrete transfer functions B_β(z)/(z^δ A(z)) and the controller polynomials R(z),
// S(z), T(z) of Eqs. 7–9.

#include <complex>
#include <vector>

namespace feedplan::control {

//! c[0] z^d + c[1] z^(d−1) + … + c[d].
struct Polynomial {
  std::vector<double> coefficients;  //!< highest power first; empty: the zero polynomial
};

//! d, the highest power held (the leading coefficient may be 0); −1 for the zero polynomial.
int degree(const Polynomial& p);

//! The coefficient of z^power (0 for powers not held).
double coefficient(const Polynomial& p, int power);

//! p(z) at a real z, by Horner.
double evaluate(const Polynomial& p, double z);

//! a(z) · b(z).
Polynomial multiply(const Polynomial& a, const Polynomial& b);

//! factor · p(z).
Polynomial scaled(const Polynomial& p, double factor);

//! The monic Π (z − r_i). `roots` must hold every complex root with its conjugate (asserted to 1e-9 in the
//! imaginary part of the product) so that the coefficients are real.
Polynomial monic_from_roots(const std::vector<std::complex<double>>& roots);

//! The roots of p (degree ≥ 1, leading coefficient not 0; asserted), as the eigenvalues of its companion
//! matrix; a first-degree p is solved directly.
std::vector<std::complex<double>> roots(const Polynomial& p);

}  // namespace feedplan::control
