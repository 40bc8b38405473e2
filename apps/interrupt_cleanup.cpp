#include "interrupt_cleanup.h"

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <ctime>
#include <fcntl.h>
#include <initializer_list>
#include <sys/wait.h>
#include <unistd.h>

#include "svo/core/pending_files.h"
#include "svo/core/slot_table.h"

namespace svo::app {
namespace {

constexpr size_t kPathBytes = 4096;

struct Child {
    pid_t pid = 0;
    std::atomic<bool> hasFiles{false}; // lock and leftover below are set
    char lock[kPathBytes];
    char leftover[kPathBytes];
};
SlotTable<Child> children;

void say(const char* text) noexcept
{
    const size_t n = std::strlen(text);
    [[maybe_unused]] const ssize_t written = ::write(STDERR_FILENO, text, n);
}

/// Whether the file at `path` holds `pid` as text (an X server's lock file:
/// the pid, right-aligned, and a newline). open, read and close only.
bool holdsPid(const char* path, pid_t pid) noexcept
{
    const int fd = ::open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0) return false;
    char text[32];
    const ssize_t n = ::read(fd, text, sizeof text - 1);
    ::close(fd);
    if (n <= 0) return false;
    long value = 0;
    bool digits = false;
    for (ssize_t i = 0; i < n; ++i) {
        if (text[i] >= '0' && text[i] <= '9') {
            value = value * 10 + (text[i] - '0');
            digits = true;
        } else if (digits || (text[i] != ' ' && text[i] != '\t')) {
            break;
        }
    }
    return digits && value == long(pid);
}

/// A reaped child's files that it did not remove itself: an X server that
/// dies abnormally (svo has seen one stopped mid-render leave its socket)
/// keeps its lock, which names it, and its socket.
void removeLeftovers(Child& c) noexcept
{
    if (!c.hasFiles.load() || !holdsPid(c.lock, c.pid)) return;
    ::unlink(c.leftover);
    ::unlink(c.lock);
}

extern "C" void onInterrupt(int sig)
{
    if (!claimInterrupt()) return; // the outputs are being committed: the run ends as it is
    say(sig == SIGINT ? "svo: interrupted (SIGINT)\n" : "svo: terminated (SIGTERM)\n");
    cleanUpForExit();
    ::_exit(128 + sig);
}

} // namespace

int registerChild(pid_t pid) noexcept
{
    return children.add([&](Child& c) {
        c.pid = pid;
        c.hasFiles.store(false);
    });
}

void setChildFiles(int slot, const char* lock, const char* leftover) noexcept
{
    Child* c = children.find(slot);
    if (!c || std::strlen(lock) >= kPathBytes || std::strlen(leftover) >= kPathBytes) return;
    std::memcpy(c->lock, lock, std::strlen(lock) + 1);
    std::memcpy(c->leftover, leftover, std::strlen(leftover) + 1);
    c->hasFiles.store(true); // after the paths: the handler reads them only then
}

void releaseChild(int slot) noexcept
{
    Child* c = children.find(slot);
    if (!c) return;
    removeLeftovers(*c);
    children.remove(slot);
}

void cleanUpForExit() noexcept
{
    removeTemporaries();
    children.forEachReady([](const Child& c) { ::kill(c.pid, SIGTERM); });
    children.forEachReady([](Child& c) {
        // Give the child time to remove its own files (Xvfb's socket and lock).
        for (int i = 0; i < 200; ++i) {
            const pid_t r = ::waitpid(c.pid, nullptr, WNOHANG);
            if (r == c.pid) removeLeftovers(c);
            if (r != 0) break; // reaped, or not ours to wait for
            const timespec tenMs{0, 10'000'000};
            ::nanosleep(&tenMs, nullptr);
        }
    });
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

} // namespace svo::app
