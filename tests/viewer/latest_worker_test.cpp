#include <doctest/doctest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>

#include "lapis/viewer/latest_worker.h"

using lapis::viewer::LatestWorker;
using namespace std::chrono_literals;

TEST_CASE("viewer: the latest worker drops stale jobs and delivers the newest result") {
  LatestWorker<int> worker;
  std::atomic<bool> release{false}, started{false};
  std::atomic<int> ran{0};
  worker.submit([&] {
    started = true;
    while (!release) std::this_thread::sleep_for(1ms);
    ++ran;
    return 1;
  });
  // Wait until job 1 runs (not only until it is queued: on a loaded machine the worker
  // thread may start it much later, and the jobs below would then replace it).
  while (!started) std::this_thread::sleep_for(1ms);
  for (int k = 2; k <= 10; ++k)
    worker.submit([&ran, k] {
      ++ran;
      return k;
    });
  CHECK(worker.busy());
  release = true;
  worker.wait();
  CHECK(!worker.busy());
  // Job 1 ran (it had started), jobs 2..9 were replaced before starting, job 10 ran.
  CHECK(ran == 2);
  const auto r = worker.take();
  REQUIRE(r.has_value());
  CHECK(*r == 10);
  CHECK(!worker.take().has_value());  // taken once
  CHECK(worker.submitted() == 10);
  CHECK(worker.completed() == 2);
}

TEST_CASE("viewer: the latest worker hands a job's exception to take()") {
  LatestWorker<int> worker;
  worker.submit([]() -> int { throw std::runtime_error("solve failed"); });
  worker.wait();
  CHECK_THROWS_WITH(worker.take(), "solve failed");
  worker.submit([] { return 7; });
  worker.wait();
  CHECK(worker.take() == 7);
}

TEST_CASE("viewer: a latest worker job posts a first result before its own, and sees when a newer job waits") {
  LatestWorker<int> worker;
  std::atomic<bool> posted{false}, newer_submitted{false};
  std::atomic<int> superseded_seen{-1};
  worker.submit([&] {
    worker.post(1);  // a preview
    posted = true;
    while (!newer_submitted) std::this_thread::sleep_for(1ms);
    superseded_seen = worker.superseded() ? 1 : 0;
    return 2;
  });
  while (!posted) std::this_thread::sleep_for(1ms);
  CHECK(worker.busy());
  CHECK(worker.take() == 1);  // the preview, while the job still runs
  CHECK_FALSE(worker.superseded());
  worker.submit([] { return 3; });
  newer_submitted = true;
  worker.wait();
  CHECK(superseded_seen == 1);
  CHECK(worker.take() == 3);  // the newest; the first job's own result was replaced
  CHECK_FALSE(worker.superseded());
  CHECK(worker.completed() == 2);
}
