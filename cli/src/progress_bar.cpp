#include "progress_bar.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace feedplan::cli {

namespace {

// "42 s", "3 min 20 s", "1 h 05 min".
std::string duration_text(double seconds) {
  const long s = std::lround(std::max(seconds, 0.0));
  char text[32];
  if (s < 60) {
    std::snprintf(text, sizeof text, "%ld s", s);
  } else if (s < 3600) {
    std::snprintf(text, sizeof text, "%ld min %02ld s", s / 60, s % 60);
  } else {
    std::snprintf(text, sizeof text, "%ld h %02ld min", s / 3600, (s % 3600) / 60);
  }
  return text;
}

}  // namespace

ProgressBar::ProgressBar(std::string label, bool terminal)
    : label_(std::move(label)), started_(std::chrono::steady_clock::now()), terminal_(terminal) {}

ProgressBar::ProgressBar(std::string label) : ProgressBar(std::move(label), isatty(STDERR_FILENO) != 0) {}

std::string ProgressBar::line(const std::string& label, double fraction, double elapsed_s) {
  constexpr int kWidth = 30;
  const double f = std::clamp(fraction, 0.0, 1.0);
  const int filled = static_cast<int>(std::lround(f * kWidth));
  std::string text = label + " [" + std::string(filled, '#') + std::string(kWidth - filled, '.') + "] ";
  char percent[16];
  std::snprintf(percent, sizeof percent, "%3d %%", static_cast<int>(std::floor(f * 100.0)));
  text += percent;
  text += "  " + duration_text(elapsed_s);
  if (f >= 1.0) return text;
  if (elapsed_s < 1.0 || f < 0.01) return text + ", estimating the time left";
  return text + ", about " + duration_text(elapsed_s * (1.0 - f) / f) + " left";
}

void ProgressBar::operator()(double fraction) {
  if (!terminal_) return;
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
  const bool done = fraction >= 1.0;
  if (done && !shown_) return;
  if (!done && (elapsed < 0.5 || elapsed - last_drawn_s_ < 0.2)) return;
  shown_ = true;
  last_drawn_s_ = elapsed;
  // \033[K clears what a longer earlier line left.
  std::fprintf(stderr, "\r%s\033[K%s", line(label_, fraction, elapsed).c_str(), done ? "\n" : "");
  std::fflush(stderr);
}

}  // namespace feedplan::cli
