// The fuzz targets' operator new: a request larger than the machine's
// memory throws std::bad_alloc, as it does in the Release build (Linux
// refuses such an allocation, glibc returns null, new throws), instead of
// the AddressSanitizer report that would end the run. Libraries that size
// a buffer from a corrupt file (OpenVDB's blosc reader asks for terabytes)
// then take the same error path a user's run takes: the reader's "claims
// more data than can be allocated". Smaller requests go to malloc, which
// AddressSanitizer checks, and libFuzzer's -malloc_limit_mb still reports
// any single allocation above its limit.

#include <unistd.h>

#include <cstdlib>
#include <new>

namespace {

std::size_t physical_memory() {
  static const std::size_t bytes =
      static_cast<std::size_t>(sysconf(_SC_PHYS_PAGES)) * static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
  return bytes;
}

void* allocate(std::size_t size) {
  if (size > physical_memory()) throw std::bad_alloc();
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}

}  // namespace

void* operator new(std::size_t size) { return allocate(size); }
void* operator new[](std::size_t size) { return allocate(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  try {
    return allocate(size);
  } catch (const std::bad_alloc&) {
    return nullptr;
  }
}
void* operator new[](std::size_t size, const std::nothrow_t& tag) noexcept { return operator new(size, tag); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
