// Runs an app's expensive update (regrow strands, solve a deformation) on one background
// thread so the UI never waits: submit() queues a job, replacing any queued job that has
// not started (stale requests are dropped, only the newest matters); take() hands the newest
// finished result to the UI thread once. A job may post() a partial result before its own. Exceptions from a job are
// delivered by take().
#pragma once

#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>

namespace lapis::viewer {

template <class Result>
class LatestWorker {
 public:
  LatestWorker() : thread_([this] { loop(); }) {}
  ~LatestWorker() {
    {
      std::lock_guard lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    thread_.join();
  }
  LatestWorker(const LatestWorker&) = delete;
  LatestWorker& operator=(const LatestWorker&) = delete;

  // Queues `job`; a queued job that has not started yet is dropped in its favour.
  void submit(std::function<Result()> job) {
    {
      std::lock_guard lock(mutex_);
      queued_ = std::move(job);
      ++submitted_;
    }
    wake_.notify_all();
  }

  // From inside a running job: hands `partial` over now, as the newest result (a first look at
  // what the job makes; on_done runs as after a job). The job's own result follows it.
  void post(Result partial) {
    std::lock_guard lock(mutex_);
    done_ = std::move(partial);
    if (on_done_) on_done_();
  }

  // The newest finished result not yet taken; rethrows what its job threw.
  std::optional<Result> take() {
    std::lock_guard lock(mutex_);
    if (error_) {
      std::exception_ptr e = error_;
      error_ = nullptr;
      std::rethrow_exception(e);
    }
    std::optional<Result> out = std::move(done_);
    done_.reset();
    return out;
  }

  // True while a newer job waits for the running one (which may then stop early).
  bool superseded() const {
    std::lock_guard lock(mutex_);
    return queued_.has_value();
  }

  // True while a job is queued or running (replays wait for this before screenshots).
  bool busy() const {
    std::lock_guard lock(mutex_);
    return queued_ || running_;
  }

  // Blocks until idle (tests, batch runs).
  void wait() {
    std::unique_lock lock(mutex_);
    idle_.wait(lock, [this] { return !queued_ && !running_; });
  }

  // Called on the worker thread after each job (e.g. Viewer::wake, so the UI shows the
  // result at once instead of at its next timed redraw). Must not call back into the worker.
  void set_on_done(std::function<void()> on_done) {
    std::lock_guard lock(mutex_);
    on_done_ = std::move(on_done);
  }
  long submitted() const {
    std::lock_guard lock(mutex_);
    return submitted_;
  }
  long completed() const {
    std::lock_guard lock(mutex_);
    return completed_;
  }

 private:
  void loop() {
    std::unique_lock lock(mutex_);
    for (;;) {
      wake_.wait(lock, [this] { return stop_ || queued_; });
      if (stop_) return;
      std::function<Result()> job = std::move(*queued_);
      queued_.reset();
      running_ = true;
      lock.unlock();
      std::optional<Result> result;
      std::exception_ptr error;
      try {
        result = job();
      } catch (...) {
        error = std::current_exception();
      }
      lock.lock();
      running_ = false;
      ++completed_;
      if (error)
        error_ = error;
      else
        done_ = std::move(result);
      if (!queued_) idle_.notify_all();
      if (on_done_) on_done_();  // under the lock: set_on_done cannot race it
    }
  }

  mutable std::mutex mutex_;
  std::condition_variable wake_, idle_;
  std::optional<std::function<Result()>> queued_;
  std::optional<Result> done_;
  std::exception_ptr error_;
  std::function<void()> on_done_;
  bool running_ = false, stop_ = false;
  long submitted_ = 0, completed_ = 0;
  std::thread thread_;  // last: starts after the members it uses exist
};

}  // namespace lapis::viewer
