#pragma once
// A progress bar on stderr for long batch jobs: drawn only when stderr is a terminal, and only once the job
// has run for a second (short jobs print nothing). Workers bump counter(); a thread redraws ten times a second.
#include <fmt/format.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <string>
#include <thread>
#include <unistd.h>

namespace radchain::cli {

class Progress {
 public:
  explicit Progress(std::string label) : label_(std::move(label)) {}
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;
  ~Progress() { stop(); }

  std::atomic<std::size_t>* counter() { return &done_; }

  // Starts watching a job of `total` points.
  void start(std::size_t total) {
    total_ = total;
    if (total < 2 || !::isatty(STDERR_FILENO)) return;
    started_ = std::chrono::steady_clock::now();
    thread_ = std::thread([this] { loop(); });
  }

  void stop() {
    {
      std::lock_guard lock(mutex_);
      stopping_ = true;
    }
    wake_.notify_all();
    if (thread_.joinable()) thread_.join();
    if (drawn_) std::fputs("\r\033[K", stderr);
  }

 private:
  void loop() {
    std::unique_lock lock(mutex_);
    while (!wake_.wait_for(lock, std::chrono::milliseconds(100), [this] { return stopping_; })) {
      const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
      if (elapsed < 1.0) continue;  // a short job prints nothing
      const std::size_t done = std::min(done_.load(std::memory_order_relaxed), total_);
      const double fraction = static_cast<double>(done) / static_cast<double>(total_);
      constexpr int width = 30;
      const int filled = static_cast<int>(fraction * width);
      const std::string left = done > 0 ? fmt::format(", {:.0f} s left", elapsed * (1 - fraction) / fraction) : "";
      std::fputs(fmt::format("\r\033[K{} [{}{}] {:3.0f}% {}/{}  {:.1f} s{}", label_, std::string(filled, '#'),
                             std::string(width - filled, '.'), 100 * fraction, done, total_, elapsed, left)
                     .c_str(),
                 stderr);
      std::fflush(stderr);
      drawn_ = true;
    }
  }

  std::string label_;
  std::atomic<std::size_t> done_{0};
  std::size_t total_ = 0;
  std::chrono::steady_clock::time_point started_;
  std::thread thread_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;
  bool drawn_ = false;
};

}  // namespace radchain::cli
