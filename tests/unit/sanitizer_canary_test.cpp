// A deliberate data race, hidden from the ordinary runs ([.]): scripts/sanitize.sh thread runs it
// and requires ThreadSanitizer to report it, so that a thread-sanitizer run that finds nothing in
// the real tests means something (with the sanitizer off the setup would be blind; against an
// uninstrumented libtbb it would drown in false reports instead).
#include <catch2/catch.hpp>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <thread>

TEST_CASE("a data race between TBB tasks (ThreadSanitizer must report it)", "[.][tsan-canary]") {
  std::atomic<int> started{0};
  int unguarded = 0;
  // Two tasks that each wait for the other to start, so that two threads take part. Up to 30 s:
  // under ThreadSanitizer on a busy two-core machine the second worker once took longer than 1 s to
  // start, the tasks ran one after the other, and there was no race to report.
  tbb::parallel_for(tbb::blocked_range<int>(0, 2, 1), [&](const tbb::blocked_range<int>&) {
    ++started;
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (started.load() < 2 && std::chrono::steady_clock::now() < give_up) std::this_thread::yield();
    unguarded += 1;
  });
  CHECK(unguarded <= 2);
}
