#include "studies/progress_bar.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <sstream>

namespace softarm::studies {

namespace {
std::string duration_text(double s) {
  std::ostringstream o;
  if (s < 90) o << static_cast<int>(std::round(s)) << " s";
  else if (s < 5400) o << static_cast<int>(s / 60) << " min " << static_cast<int>(std::fmod(s, 60)) << " s";
  else o << static_cast<int>(s / 3600) << " h " << static_cast<int>(std::fmod(s, 3600) / 60) << " min";
  return o.str();
}
}  // namespace

ProgressBar::ProgressBar(std::ostream& out, std::string name, int total, int already_done,
                         std::chrono::steady_clock::time_point start, int concurrency)
    : out_(out), name_(std::move(name)), total_(total), done_(already_done), concurrency_(std::max(1, concurrency)),
      terminal_(&out == &std::cerr ? ::isatty(2) : &out == &std::cout ? ::isatty(1) : false),
      start_(start) {
  if (already_done > 0) out_ << name_ << ": " << already_done << " of " << total_ << " points already in the results file\n";
  draw("");
}

void ProgressBar::advance(bool failed, const std::string& what) {
  ++done_;
  ++done_here_;
  if (failed) ++failed_;
  draw(what);
}

void ProgressBar::draw(const std::string& what) {
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  constexpr int kWidth = 24;
  const int filled = total_ ? kWidth * done_ / total_ : kWidth;
  std::ostringstream line;
  line << name_ << " [" << std::string(filled, '#') << std::string(kWidth - filled, '-') << "] " << done_ << "/"
       << total_;
  if (failed_) line << " (" << failed_ << " failed)";
  line << "  " << duration_text(elapsed);
  if (done_here_ > 0 && done_ < total_) {
    const int side_by_side = std::min(concurrency_, total_ - (done_ - done_here_));  // this run's, at once
    line << ", ETA " << duration_text(elapsed / std::max(done_here_, side_by_side) * (total_ - done_));
  }
  if (terminal_) {
    out_ << "\r" << line.str() << "\033[K" << std::flush;
  } else if (done_here_ > 0) {
    out_ << line.str() << (what.empty() ? "" : "  " + what) << "\n" << std::flush;
  }
}

void ProgressBar::finish() {
  if (terminal_) out_ << "\n";
  out_ << std::flush;
}

fem::TaskProgress task_progress(std::ostream& out, std::string name) {
  // Made at the first call, when the total is known, timed from now, when the tasks start;
  // fem::parallel_tasks calls one at a time. The threads are counted here, before the tasks: inside
  // one, where the first call comes from, thread_count() is 1.
  auto bar = std::make_shared<std::unique_ptr<ProgressBar>>();
  return [&out, name = std::move(name), bar, start = std::chrono::steady_clock::now(),
          side_by_side = fem::thread_count()](int done, int total) {
    if (!*bar) *bar = std::make_unique<ProgressBar>(out, name, total, 0, start, side_by_side);
    (*bar)->advance(false, "");
    if (done == total) (*bar)->finish();
  };
}

}  // namespace softarm::studies
