#include "draco_trial_decode.h"

#include <mr/core/errors.h>

#include <draco/compression/decode.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <optional>
#include <thread>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace mr::plugins::detail {
namespace {

/// What the child runs: the decode alone, under its CPU limit. It leaves
/// through _exit, so nothing of the parent (stdio buffers, atexit handlers,
/// temporary files) is touched twice.
[[noreturn]] void run_trial(std::string_view bytes, double cpu_seconds) {
  for (int signal_number : {SIGINT, SIGTERM, SIGHUP}) std::signal(signal_number, SIG_DFL);
  const rlimit no_core{0, 0};
  setrlimit(RLIMIT_CORE, &no_core);
  const auto soft = static_cast<rlim_t>(std::max(1.0, std::round(cpu_seconds)));
  const rlimit cpu{soft, soft + 1};  // past the soft limit the kernel sends SIGXCPU
  setrlimit(RLIMIT_CPU, &cpu);
  int code = 1;
  try {
    draco::DecoderBuffer buffer;
    buffer.Init(bytes.data(), bytes.size());
    draco::Decoder decoder;
    if (decoder.DecodeMeshFromBuffer(&buffer).ok()) code = 0;
  } catch (...) {
  }
  _exit(code);
}

/// Waits for `child` until `deadline`; returns its status, or nullopt (and
/// kills it) if it is still running then. The wall-clock deadline is a
/// backstop for a child that hangs without using CPU time.
std::optional<int> wait_for(pid_t child, std::chrono::steady_clock::time_point deadline) {
  auto pause = std::chrono::microseconds(20);
  for (;;) {
    int status = 0;
    const pid_t done = waitpid(child, &status, WNOHANG);
    if (done == child) return status;
    if (done < 0 && errno != EINTR) return 0;  // not ours to wait for (SIGCHLD ignored): ended
    if (std::chrono::steady_clock::now() > deadline) {
      kill(child, SIGKILL);
      while (waitpid(child, &status, 0) < 0 && errno == EINTR) {
      }
      return std::nullopt;
    }
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, std::chrono::microseconds(10000));
  }
}

}  // namespace

void trial_decode_draco(std::string_view bytes, const std::string& source, const DracoTrialLimits& limits) {
  const double cpu_seconds = limits.seconds_for(bytes.size());
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                             std::chrono::duration<double>(4 * cpu_seconds + 5));
  const pid_t child = fork();
  if (child < 0) return;  // no process to spare: decode without the trial
  if (child == 0) run_trial(bytes, cpu_seconds);
  const std::optional<int> status = wait_for(child, deadline);
  const auto too_slow = [&] {
    char limit[32];
    std::snprintf(limit, sizeof limit, "%.1f", cpu_seconds);
    return InputError(source, std::string("not a valid Draco mesh: Draco's decoder did not finish within ") +
                                  limit +
                                  " s of CPU time (a mesh of this size decodes in a fraction of that)");
  };
  if (!status) throw too_slow();
  if (WIFSIGNALED(*status)) {
    const int signal_number = WTERMSIG(*status);
    if (signal_number == SIGXCPU || signal_number == SIGKILL) throw too_slow();
    throw InputError(source, "not a valid Draco mesh: Draco's decoder crashed on it (signal " +
                                 std::to_string(signal_number) + ")");
  }
}

}  // namespace mr::plugins::detail
