#pragma once
// The greatest speed profile along a path under pointwise speed caps and a path acceleration limit
// (docs/method.md §5.5), and the time it takes.
//
// Nodes i = 0…n−1 sit at path lengths s_i (non-decreasing). Between two nodes the acceleration is
// constant, so u = v² is linear in s there, and the constraints are
//
//   u_i ≤ cap_i²,   u_{i+1} ≤ u_i + 2 a (s_{i+1} − s_i),   u_i ≤ u_{i+1} + 2 a (s_{i+1} − s_i).
//
// A forward pass (acceleration) and a backward pass (deceleration) give the greatest u satisfying all
// of them: every feasible profile lies below it, so it is the time-optimal one (the argument of
// TOPP-RA's reachability analysis for a single path-acceleration bound). A node whose cap is 0 is a stop.

#include <vector>

namespace feedplan::planner {

//! The greatest speeds (same unit as the caps) at the nodes under `cap` and the acceleration limit
//! `accel` (speed unit² per length unit: mm/s² with mm and mm/s). `s` and `cap` have the same size;
//! s must be non-decreasing and caps ≥ 0 (asserted). Linear in the number of nodes.
std::vector<double> greatest_speeds(const std::vector<double>& s, const std::vector<double>& cap, double accel);

//! Time of the greatest profile over one interval of length ds from speed v0 to speed v1 under the cap
//! `cap` and the acceleration limit `accel`: accelerate, cruise at the cap if it is reached, decelerate
//! (a triangle or a trapezoid; exact). v0, v1 must be reachable from each other within ds (as the
//! nodes of greatest_speeds are) and ≤ cap. 0 when ds = 0.
double interval_time(double ds, double v0, double v1, double cap, double accel);

}  // namespace feedplan::planner
