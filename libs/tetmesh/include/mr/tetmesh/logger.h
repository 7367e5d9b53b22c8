#pragma once
// How the pipeline reports: one logger and one progress callback, both
// replaceable by the caller (a tool prints, a test collects, a GUI draws).
// Library code never writes to stdout or stderr itself.

#include <functional>
#include <string_view>

namespace mr::tetmesh {

enum class LogLevel { debug, info, warning };

struct Logger {
  /// Receives every message; empty: messages are dropped.
  std::function<void(LogLevel, std::string_view)> on_message;
  /// Receives (stage name, fraction done in [0, 1]); empty: ignored.
  std::function<void(std::string_view, double)> on_progress;

  void log(LogLevel level, std::string_view text) const {
    if (on_message) on_message(level, text);
  }
  void progress(std::string_view stage, double fraction) const {
    if (on_progress) on_progress(stage, fraction);
  }
};

}  // namespace mr::tetmesh
