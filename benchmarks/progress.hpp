#pragma once
// Progress of a long benchmark or stress run, printed to stderr: done/total, elapsed, ETA.
//
//   Progress progress("pareto", total_work);      // work in any unit (runs, estimated steps)
//   progress.advance(work_of_this_item, "cloth64 SymplecticEuler dt=1e-4");
//
// The ETA assumes the remaining work costs what the done work cost per unit. On a terminal the
// line is rewritten in place; otherwise (a log file, CI) one line is printed every `every`
// seconds at most, and at the end.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>

namespace massspring::bench {

class Progress {
 public:
  Progress(std::string what, double total, double every = 10.0)
      : what_(std::move(what)),
        total_(total),
        every_(every),
        tty_(isatty(fileno(stderr)) != 0),
        start_(std::chrono::steady_clock::now()) {}

  /// Marks `work` more as done; `label` names the item just finished.
  void advance(double work, const std::string& label) {
    done_ += work;
    ++items_;
    const double elapsed = seconds();
    const bool last = done_ >= total_;
    if (!tty_ && !last && elapsed - printed_ < every_) return;
    printed_ = elapsed;
    const double eta = done_ > 0 ? elapsed / done_ * (total_ - done_) : 0;
    std::fprintf(stderr, "%s[%s] %5.1f%% (%d done)  elapsed %s  ETA %s  %s%s",
                 tty_ ? "\r\033[K" : "", what_.c_str(), 100.0 * done_ / total_, items_,
                 clock(elapsed).c_str(), clock(eta > 0 ? eta : 0).c_str(), label.c_str(),
                 tty_ && !last ? "" : "\n");
    std::fflush(stderr);
  }
  /// Seconds since construction.
  [[nodiscard]] double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  static std::string clock(double s) {
    char buf[32];
    const long t = long(s + 0.5);
    std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", t / 3600, (t / 60) % 60, t % 60);
    return buf;
  }
  std::string what_;
  double total_, every_;
  bool tty_;
  std::chrono::steady_clock::time_point start_;
  double done_ = 0, printed_ = -1e300;
  int items_ = 0;
};

}  // namespace massspring::bench
