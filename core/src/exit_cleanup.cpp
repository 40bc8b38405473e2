#include "svo/core/exit_cleanup.h"

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <ctime>
#include <initializer_list>
#include <sys/wait.h>
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
struct ChildSlot {
    std::atomic<int> state{kFree};
    pid_t pid = 0;
};
TemporarySlot temporaries[kSlots];
ChildSlot children[kSlots];

template <typename Slot>
int claim(Slot* slots) noexcept
{
    for (int i = 0; i < kSlots; ++i) {
        int expected = kFree;
        if (slots[i].state.compare_exchange_strong(expected, kWriting)) return i;
    }
    return -1;
}

void say(const char* text) noexcept
{
    const size_t n = std::strlen(text);
    [[maybe_unused]] const ssize_t written = ::write(STDERR_FILENO, text, n);
}

extern "C" void onInterrupt(int sig)
{
    say(sig == SIGINT ? "svo: interrupted (SIGINT)\n" : "svo: terminated (SIGTERM)\n");
    cleanUpForExit();
    ::_exit(128 + sig);
}

} // namespace

int registerTemporary(const char* path) noexcept
{
    const size_t n = std::strlen(path);
    if (n >= kPathBytes) return -1;
    const int slot = claim(temporaries);
    if (slot < 0) return -1;
    std::memcpy(temporaries[slot].path, path, n + 1);
    temporaries[slot].state.store(kReady);
    return slot;
}

void releaseTemporary(int slot) noexcept
{
    if (slot >= 0 && slot < kSlots) temporaries[slot].state.store(kFree);
}

int registerChild(pid_t pid) noexcept
{
    const int slot = claim(children);
    if (slot < 0) return -1;
    children[slot].pid = pid;
    children[slot].state.store(kReady);
    return slot;
}

void releaseChild(int slot) noexcept
{
    if (slot >= 0 && slot < kSlots) children[slot].state.store(kFree);
}

void cleanUpForExit() noexcept
{
    // A temporary renamed just before we got here is simply not found.
    for (TemporarySlot& t : temporaries)
        if (t.state.load() == kReady) ::unlink(t.path);
    for (ChildSlot& c : children)
        if (c.state.load() == kReady) ::kill(c.pid, SIGTERM);
    for (ChildSlot& c : children) {
        if (c.state.load() != kReady) continue;
        // Give the child time to remove its own files (Xvfb's socket and lock).
        for (int i = 0; i < 200; ++i) {
            const pid_t r = ::waitpid(c.pid, nullptr, WNOHANG);
            if (r != 0) break; // reaped, or not ours to wait for
            const timespec tenMs{0, 10'000'000};
            ::nanosleep(&tenMs, nullptr);
        }
    }
}

void installInterruptCleanup()
{
    struct sigaction action {};
    action.sa_handler = onInterrupt;
    sigemptyset(&action.sa_mask);
    // The handler exits, so a second signal must not interrupt its clean-up.
    sigaddset(&action.sa_mask, SIGINT);
    sigaddset(&action.sa_mask, SIGTERM);
    for (const int sig : {SIGINT, SIGTERM}) {
        // A signal ignored at start (a job run with nohup, or with & by a
        // non-interactive shell) stays ignored, as the shell intended.
        struct sigaction previous {};
        if (::sigaction(sig, nullptr, &previous) == 0 && previous.sa_handler == SIG_IGN) continue;
        ::sigaction(sig, &action, nullptr);
    }
}

} // namespace svo
