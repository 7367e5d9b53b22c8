#pragma once
// Typed exceptions. Library code throws these; only a tool's main() turns
// them into messages and exit codes (InputError and UsageError: 2, others: 1).

#include <stdexcept>
#include <string>
#include <string_view>

namespace mr {

/// Base of every error the library reports on purpose.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A file that cannot be read as the mesh it claims to be: missing, empty,
/// truncated, inconsistent, or in an unknown format. The message names the file.
class InputError : public Error {
 public:
  InputError(const std::string& path, const std::string& problem)
      : Error(path + ": " + problem), path_(path), problem_(problem) {}
  const std::string& path() const { return path_; }
  const std::string& problem() const { return problem_; }

 private:
  std::string path_;
  std::string problem_;
};

/// Bad options or arguments given by the caller.
class UsageError : public Error {
 public:
  using Error::Error;
};

/// A run that could not complete on valid input (write failure, a stage
/// that could not reach its contract).
class RunError : public Error {
 public:
  using Error::Error;
};

/// The message of an exception thrown by a library, without the tag some
/// libraries put first ("[json.exception.type_error.316] "): for messages of
/// ours that say which file and what failed, followed by the library's detail.
inline std::string library_error_text(const std::exception& e) {
  std::string_view text = e.what();
  if (text.starts_with('[')) {
    if (const auto close = text.find("] "); close != std::string_view::npos) text.remove_prefix(close + 2);
  }
  return text.empty() ? std::string("no detail given") : std::string(text);
}

}  // namespace mr
