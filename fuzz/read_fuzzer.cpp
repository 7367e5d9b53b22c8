// libFuzzer target for one reader, chosen at compile time by MR_FUZZ_TARGET
// (a name in fuzz_entry.h's reader_targets). See fuzz_entry.h for what passes.

#include "fuzz_entry.h"

#include <mr/io/default_registry.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>

#ifndef MR_FUZZ_TARGET
#error "MR_FUZZ_TARGET must name the reader target"
#endif

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const mr::io::Registry registry = mr::io::make_default_registry();
  static const char* format = [] {
    const char* found = mr::fuzz::reader_format(MR_FUZZ_TARGET);
    if (!found) {
      std::fprintf(stderr, "unknown fuzz target %s\n", MR_FUZZ_TARGET);
      std::abort();
    }
    return found;
  }();
  mr::fuzz::read_as(registry, format, std::string_view(reinterpret_cast<const char*>(data), size));
  return 0;
}
