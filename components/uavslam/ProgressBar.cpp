#include "ProgressBar.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace uavslam::cli {
namespace {

constexpr int kBarWidth = 24;

std::string seconds_text(double seconds) {
  char text[32];
  if (seconds >= 3600.0) {
    std::snprintf(text, sizeof text, "%dh%02dm", int(seconds / 3600), int(seconds / 60) % 60);
  } else if (seconds >= 60.0) {
    std::snprintf(text, sizeof text, "%dm%02ds", int(seconds / 60), int(seconds) % 60);
  } else {
    std::snprintf(text, sizeof text, "%.0fs", seconds);
  }
  return text;
}

}  // namespace

ProgressBar::ProgressBar(std::string label, std::size_t total, std::string unit, std::ostream& out,
                         bool terminal)
    : label_(std::move(label)),
      total_(total),
      unit_(std::move(unit)),
      out_(out),
      terminal_(terminal) {}

void ProgressBar::update(std::size_t done) {
  if (terminal_) {
    const Clock::time_point now = Clock::now();
    if (now - last_draw_ < std::chrono::milliseconds(200)) return;
    last_draw_ = now;
    draw(done, false);
  } else if (total_ > 0 && done >= next_plain_line_) {
    draw(done, false);
    next_plain_line_ = done + std::max<std::size_t>(1, total_ / 10);
  }
}

void ProgressBar::finish(std::size_t done) {
  if (terminal_ || done != last_drawn_) draw(done, true);
}

std::string ProgressBar::line(std::size_t done) const {
  const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
  const double rate = elapsed > 0.0 ? double(done) / elapsed : 0.0;
  char text[160];
  std::string bar;
  if (total_ > 0) {
    const double fraction = std::min(1.0, double(done) / double(total_));
    if (terminal_) {
      const int filled = int(std::lround(fraction * kBarWidth));
      bar = "[" + std::string(filled, '#') + std::string(kBarWidth - filled, '.') + "] ";
    }
    const double left = rate > 0.0 ? double(total_ - std::min(done, total_)) / rate : 0.0;
    std::snprintf(text, sizeof text, "%3.0f%% %zu/%zu %s, %.0f %s/s, %s elapsed, %s left",
                  100.0 * fraction, done, total_, unit_.c_str(), rate, unit_.c_str(),
                  seconds_text(elapsed).c_str(), seconds_text(left).c_str());
  } else {
    std::snprintf(text, sizeof text, "%zu %s, %.0f %s/s, %s elapsed", done, unit_.c_str(), rate,
                  unit_.c_str(), seconds_text(elapsed).c_str());
  }
  return "  " + label_ + " " + bar + text;
}

void ProgressBar::draw(std::size_t done, bool final_line) {
  last_drawn_ = done;
  if (terminal_) {
    // \033[K clears what a longer previous line left behind.
    out_ << '\r' << line(done) << "\033[K" << (final_line ? "\n" : "") << std::flush;
  } else {
    out_ << line(done) << '\n' << std::flush;
  }
}

}  // namespace uavslam::cli
