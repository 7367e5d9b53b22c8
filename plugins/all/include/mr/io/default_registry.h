#pragma once
// A registry holding every format plugin this build was configured with.

#include <mr/io/registry.h>

namespace mr::io {

Registry make_default_registry();

}  // namespace mr::io
