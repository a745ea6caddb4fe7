#pragma once
// A continuous-time linear plant of second order with one input and one output, ẋ = A x + B u, y = C x:
// the form in which seed 004 (Rubio & De la Sen 2007) has both its milling plant (Eq. 3) and its reference
// model (Eq. 6) before it samples them under a fractional-order hold (fractional_order_hold.hpp).

#include <array>

namespace feedplan::control {

//! ẋ = A x + B u, y = C x, with two states.
struct ContinuousSystem {
  std::array<std::array<double, 2>, 2> a{};  //!< A, 1/s, row by row
  std::array<double, 2> b{};                 //!< B: state rate per unit of input, per s
  std::array<double, 2> c{};                 //!< C: output per unit of state
};

}  // namespace feedplan::control
