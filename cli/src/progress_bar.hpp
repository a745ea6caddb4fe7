#pragma once
// A progress line on stderr for the long jobs (simulate, plan --simulate, loop), only when stderr is a
// terminal: a bar, the percentage, the time so far and an estimate of the time left (elapsed × the
// share not yet done / the share done — the jobs weight their parts by cost, so the share is close to
// the share of the time). Drawn from the first report after half a second, at most 5 times a second.

#include <chrono>
#include <string>

namespace feedplan::cli {

//! One job's progress line.
class ProgressBar {
 public:
  //! `label` starts the line ("simulating"); `terminal`: draw at all (default: stderr is a terminal).
  explicit ProgressBar(std::string label, bool terminal);
  explicit ProgressBar(std::string label);

  //! The share of the job done (0..1); 1 ends the line.
  void operator()(double fraction);

  //! The line for `fraction` after `elapsed_s`, e.g. "simulating [####......] 42 %  12 s, about 17 s
  //! left"; "estimating" before 1 s or 1 % (exposed for the tests).
  static std::string line(const std::string& label, double fraction, double elapsed_s);

 private:
  std::string label_;
  std::chrono::steady_clock::time_point started_;
  double last_drawn_s_ = -1.0;
  bool terminal_ = false;
  bool shown_ = false;
};

}  // namespace feedplan::cli
