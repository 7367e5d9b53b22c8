#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace mr::tools {

/// `format-convert IN OUT [options]`; returns the exit code.
int format_convert(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace mr::tools
