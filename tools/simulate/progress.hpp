#pragma once
// massspring-simulate's progress lines: while a run goes on, one line on stdout every `interval`
// seconds of wall-clock time (never more often), flushed, so that a long run is not silent:
//
//   step 1200 of 3000 (40%): 6 s of 15 s simulated; 12 s elapsed, about 18 s left

#include <chrono>
#include <cstdio>

namespace simulate {

class Progress {
 public:
  /// @param interval  wall-clock seconds between lines; 0: no lines
  /// @param steps     the steps of the run; @param dt its step [s]
  Progress(double interval, int steps, double dt)
      : interval_(interval), steps_(steps), dt_(dt), start_(Clock::now()), last_(start_) {}

  /// After step `done` (1-based) of the run: a line when `interval` has passed since the last.
  void step_done(int done) {
    if (!(interval_ > 0)) return;
    const Clock::time_point now = Clock::now();
    if (seconds(last_, now) < interval_) return;
    last_ = now;
    const double elapsed = seconds(start_, now);
    const double left = elapsed * double(steps_ - done) / double(done);
    std::printf(
        "step %d of %d (%.0f%%): %.4g s of %.4g s simulated; %.1f s elapsed, about %.1f s "
        "left\n",
        done, steps_, 100.0 * double(done) / double(steps_), dt_ * double(done),
        dt_ * double(steps_), elapsed, left);
    std::fflush(stdout);
  }

 private:
  using Clock = std::chrono::steady_clock;
  static double seconds(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
  }
  double interval_;
  int steps_;
  double dt_;
  Clock::time_point start_, last_;
};

}  // namespace simulate
