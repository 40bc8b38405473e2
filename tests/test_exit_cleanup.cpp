// The interrupt clean-up's children (exit_cleanup.h): a child that dies
// without removing its files (an X server's lock and socket) has them removed
// once reaped, and only when the lock names that child.
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

pid_t startSleeper()
{
    const pid_t pid = fork();
    if (pid == 0) {
        execlp("sleep", "sleep", "30", static_cast<char*>(nullptr));
        _exit(127);
    }
    return pid;
}

void writeFile(const std::string& path, const std::string& text)
{
    std::ofstream(path) << text;
}

} // namespace

TEST(ExitCleanup, AChildKilledBeforeItsCleanUpHasItsFilesRemoved)
{
    svo::test::TempDir tmp("exit-cleanup");
    const pid_t pid = startSleeper();
    ASSERT_GT(pid, 0);
    const int slot = svo::registerChild(pid);
    ASSERT_GE(slot, 0);
    // As an X server writes it: the pid right-aligned in 10 columns.
    writeFile(tmp.path("lock"), std::string(10 - std::to_string(pid).size(), ' ') + std::to_string(pid) + "\n");
    writeFile(tmp.path("socket"), "");
    svo::setChildFiles(slot, tmp.path("lock").c_str(), tmp.path("socket").c_str());
    kill(pid, SIGKILL); // no chance to remove anything itself
    waitpid(pid, nullptr, 0);
    svo::releaseChild(slot);
    EXPECT_FALSE(fs::exists(tmp.path("lock")));
    EXPECT_FALSE(fs::exists(tmp.path("socket")));
}

TEST(ExitCleanup, FilesOfAnotherProcessAreKept)
{
    svo::test::TempDir tmp("exit-cleanup");
    const pid_t pid = startSleeper();
    ASSERT_GT(pid, 0);
    const int slot = svo::registerChild(pid);
    ASSERT_GE(slot, 0);
    // The lock of another server (this process's pid), e.g. one that took the display first.
    writeFile(tmp.path("lock"), "      " + std::to_string(getpid()) + "\n");
    writeFile(tmp.path("socket"), "");
    svo::setChildFiles(slot, tmp.path("lock").c_str(), tmp.path("socket").c_str());
    kill(pid, SIGKILL);
    waitpid(pid, nullptr, 0);
    svo::releaseChild(slot);
    EXPECT_TRUE(fs::exists(tmp.path("lock")));
    EXPECT_TRUE(fs::exists(tmp.path("socket")));
}

TEST(ExitCleanup, TheInterruptCleanUpStopsTheChildAndRemovesWhatItLeft)
{
    svo::test::TempDir tmp("exit-cleanup");
    const pid_t pid = startSleeper();
    ASSERT_GT(pid, 0);
    const int slot = svo::registerChild(pid);
    ASSERT_GE(slot, 0);
    writeFile(tmp.path("lock"), std::to_string(pid) + "\n");
    writeFile(tmp.path("socket"), "");
    svo::setChildFiles(slot, tmp.path("lock").c_str(), tmp.path("socket").c_str());
    writeFile(tmp.path("out.tmp"), "partial");
    const int temporary = svo::registerTemporary(tmp.path("out.tmp").c_str());
    ASSERT_GE(temporary, 0);
    svo::cleanUpForExit(); // what the signal handler runs: SIGTERM, wait, reap
    EXPECT_EQ(waitpid(pid, nullptr, WNOHANG), -1); // already reaped by the clean-up
    EXPECT_FALSE(fs::exists(tmp.path("lock")));
    EXPECT_FALSE(fs::exists(tmp.path("socket")));
    EXPECT_FALSE(fs::exists(tmp.path("out.tmp")));
    svo::releaseTemporary(temporary);
    svo::releaseChild(slot);
}
