#include <mr/io/unfinished_files.h>

#include <array>
#include <atomic>
#include <climits>
#include <csignal>
#include <cstring>

#include <unistd.h>

namespace mr::io {
namespace {

struct Slot {
  std::atomic<bool> claimed{false};
  std::atomic<bool> listed{false};  // path is complete and may be unlinked
  char path[PATH_MAX] = {};
};

constexpr int kSlots = 64;

// The one piece of global state in the library: what a signal handler must see.
// constinit: ready before any code runs, so a handler never meets it half-built.
constinit std::array<Slot, kSlots> all_slots;

std::array<Slot, kSlots>& slots() { return all_slots; }

int claim_slot() {
  for (int i = 0; i < kSlots; ++i) {
    bool expected = false;
    if (slots()[i].claimed.compare_exchange_strong(expected, true)) return i;
  }
  return -1;
}

void remove_and_reraise(int signal_number) {
  remove_unfinished_files();
  std::signal(signal_number, SIG_DFL);
  std::raise(signal_number);
}

}  // namespace

UnfinishedFile::UnfinishedFile(const std::filesystem::path& path) {
  const std::string& text = path.native();
  if (text.size() >= PATH_MAX) return;
  slot_ = claim_slot();
  if (slot_ < 0) return;
  Slot& slot = slots()[slot_];
  std::memcpy(slot.path, text.c_str(), text.size() + 1);
  slot.listed.store(true);
}

UnfinishedFile::~UnfinishedFile() {
  if (slot_ < 0) return;
  Slot& slot = slots()[slot_];
  slot.listed.store(false);
  slot.claimed.store(false);
}

void remove_unfinished_files() noexcept {
  for (Slot& slot : slots())
    if (slot.listed.load()) ::unlink(slot.path);
}

void remove_unfinished_files_on_signals() {
  struct sigaction action = {};
  action.sa_handler = remove_and_reraise;
  sigemptyset(&action.sa_mask);
  for (int signal_number : {SIGINT, SIGTERM, SIGHUP}) sigaction(signal_number, &action, nullptr);
}

}  // namespace mr::io
