// The interrupt clean-up's children (exit_cleanup.h): a child that dies
// without removing its files (an X server's lock and socket) has them removed
// once reaped, and only when the lock names that child.
#include <array>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include "svo/core/exit_cleanup.h"
#include "temp_dir.h"

namespace fs = std::filesystem;

namespace {

void writeFile(const std::string& path, const std::string& text)
{
    std::ofstream(path) << text;
}

/// A child (`sleep 30`) registered for the clean-up, with a lock file and a
/// socket file in `tmp` set as its files. The lock names `lockOwner`, or the
/// child itself when 0, as an X server writes it: the pid right-aligned in
/// 10 columns.
struct RegisteredChild {
    RegisteredChild(const svo::test::TempDir& tmp, pid_t lockOwner = 0)
    {
        pid = fork();
        if (pid == 0) {
            execlp("sleep", "sleep", "30", static_cast<char*>(nullptr));
            _exit(127);
        }
        slot = pid > 0 ? svo::registerChild(pid) : -1;
        const std::string owner = std::to_string(lockOwner ? lockOwner : pid);
        writeFile(tmp.path("lock"), std::string(10 - owner.size(), ' ') + owner + "\n");
        writeFile(tmp.path("socket"), "");
        svo::setChildFiles(slot, tmp.path("lock").c_str(), tmp.path("socket").c_str());
    }
    /// Killed outright, with no chance to remove anything itself, and reaped.
    void kill() const
    {
        ::kill(pid, SIGKILL);
        waitpid(pid, nullptr, 0);
    }
    pid_t pid = -1;
    int slot = -1;
};

/// A registered child whose lock names `lockOwner` (0: itself), killed and
/// then released as svo releases a child that died: whether its lock and
/// its socket file are still there afterwards.
std::array<bool, 2> filesLeftByAKilledChild(pid_t lockOwner)
{
    svo::test::TempDir tmp("exit-cleanup");
    const RegisteredChild child(tmp, lockOwner);
    EXPECT_GT(child.pid, 0);
    EXPECT_GE(child.slot, 0);
    child.kill();
    svo::releaseChild(child.slot);
    return {fs::exists(tmp.path("lock")), fs::exists(tmp.path("socket"))};
}

} // namespace

TEST(ExitCleanup, AChildKilledBeforeItsCleanUpHasItsFilesRemoved)
{
    EXPECT_EQ(filesLeftByAKilledChild(0), (std::array<bool, 2>{false, false}));
}

TEST(ExitCleanup, FilesOfAnotherProcessAreKept)
{
    // The lock of another server (this process's pid), e.g. one that took the display first.
    EXPECT_EQ(filesLeftByAKilledChild(getpid()), (std::array<bool, 2>{true, true}));
}

TEST(ExitCleanup, TheInterruptCleanUpStopsTheChildAndRemovesWhatItLeft)
{
    svo::test::TempDir tmp("exit-cleanup");
    const RegisteredChild child(tmp);
    ASSERT_GT(child.pid, 0);
    ASSERT_GE(child.slot, 0);
    writeFile(tmp.path("out.tmp"), "partial");
    const int temporary = svo::registerTemporary(tmp.path("out.tmp").c_str());
    ASSERT_GE(temporary, 0);
    svo::cleanUpForExit(); // what the signal handler runs: SIGTERM, wait, reap
    EXPECT_EQ(waitpid(child.pid, nullptr, WNOHANG), -1); // already reaped by the clean-up
    EXPECT_FALSE(fs::exists(tmp.path("lock")));
    EXPECT_FALSE(fs::exists(tmp.path("socket")));
    EXPECT_FALSE(fs::exists(tmp.path("out.tmp")));
    svo::releaseTemporary(temporary);
    svo::releaseChild(child.slot);
}
