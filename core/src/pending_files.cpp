#include "svo/core/pending_files.h"

#include <atomic>
#include <cstring>
#include <unistd.h>

namespace svo {
namespace {

// Slot states: free, being written by its owner, ready for the handler.
enum : int { kFree = 0, kWriting = 1, kReady = 2 };
constexpr int kSlots = 64;
constexpr size_t kPathBytes = 4096;

struct TemporarySlot {
    std::atomic<int> state{kFree};
    char path[kPathBytes];
};
TemporarySlot temporaries[kSlots];

// Whether an interrupt may still end the run: the first of the signal handler
// (claimInterrupt) and finishWithoutInterrupts() to leave kRunning decides.
enum : int { kRunning = 0, kInterrupted = 1, kFinishing = 2 };
std::atomic<int> phase{kRunning};

} // namespace

int registerTemporary(const char* path) noexcept
{
    const size_t n = std::strlen(path);
    if (n >= kPathBytes) return -1;
    for (int i = 0; i < kSlots; ++i) {
        int expected = kFree;
        if (!temporaries[i].state.compare_exchange_strong(expected, kWriting)) continue;
        std::memcpy(temporaries[i].path, path, n + 1);
        temporaries[i].state.store(kReady);
        return i;
    }
    return -1;
}

void releaseTemporary(int slot) noexcept
{
    if (slot >= 0 && slot < kSlots) temporaries[slot].state.store(kFree);
}

void removeTemporaries() noexcept
{
    // A temporary renamed just before we got here is simply not found.
    for (TemporarySlot& t : temporaries)
        if (t.state.load() == kReady) ::unlink(t.path);
}

void finishWithoutInterrupts() noexcept
{
    int expected = kRunning;
    if (phase.compare_exchange_strong(expected, kFinishing) || expected == kFinishing) return;
    for (;;) ::pause(); // an interrupt came first: its handler removes the temporaries and exits
}

void allowInterrupts() noexcept
{
    int expected = kFinishing;
    phase.compare_exchange_strong(expected, kRunning);
}

bool claimInterrupt() noexcept
{
    int expected = kRunning;
    if (phase.compare_exchange_strong(expected, kInterrupted)) return true;
    if (expected == kFinishing) return false; // the outputs are being committed: the run ends as it is
    for (;;) ::pause();                        // another thread's handler is cleaning up and exits
}

} // namespace svo
