#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace mr::tools {

/// `simplify-in-envelope IN OUT [options]`: fewer faces, every output point
/// within epsilon of the input, no new defects. Exit 0 on success, 2 on bad
/// usage or unreadable input, 1 on a failed run (e.g. unwritable output).
int simplify_in_envelope(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace mr::tools
