#include "svo/core/pending_files.h"

#include <atomic>
#include <cstring>
#include <unistd.h>

#include "svo/core/slot_table.h"

namespace svo {
namespace {

constexpr size_t kPathBytes = 4096;

struct Temporary {
    char path[kPathBytes];
};
SlotTable<Temporary> temporaries;

// Whether an interrupt may still end the run: the first of the signal handler
// (claimInterrupt) and finishWithoutInterrupts() to leave kRunning decides.
enum : int { kRunning = 0, kInterrupted = 1, kFinishing = 2 };
std::atomic<int> phase{kRunning};

} // namespace

int registerTemporary(const char* path) noexcept
{
    const size_t n = std::strlen(path);
    if (n >= kPathBytes) return -1;
    return temporaries.add([&](Temporary& t) { std::memcpy(t.path, path, n + 1); });
}

void releaseTemporary(int slot) noexcept { temporaries.remove(slot); }

void removeTemporaries() noexcept
{
    // A temporary renamed just before we got here is simply not found.
    temporaries.forEachReady([](const Temporary& t) { ::unlink(t.path); });
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
