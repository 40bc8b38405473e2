// The interrupt clean-up's children (apps/interrupt_cleanup.h): a child that dies
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

#include "svo/core/atomic_file.h"
#include "svo/core/error.h"
#include "interrupt_cleanup.h"
#include "svo/core/pending_files.h"
#include "temp_dir.h"

namespace fs = std::filesystem;

namespace {

void writeFile(const std::string& path, const std::string& text)
{
    std::ofstream(path) << text;
}

std::string readFile(const std::string& path)
{
    std::ifstream in(path);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

size_t filesIn(const svo::test::TempDir& tmp)
{
    return size_t(std::distance(fs::directory_iterator(tmp.dir()), fs::directory_iterator()));
}

/// The exit status of a child that installs the interrupt clean-up, runs
/// `body`, and exits 0 if it returns.
template <typename Body>
int exitStatusOf(Body body)
{
    const pid_t pid = fork();
    if (pid == 0) {
        svo::allowInterrupts(); // whatever an earlier test in this process left
        svo::app::installInterruptCleanup();
        body();
        _exit(0);
    }
    int status = 0;
    waitpid(pid, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
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
        slot = pid > 0 ? svo::app::registerChild(pid) : -1;
        const std::string owner = std::to_string(lockOwner ? lockOwner : pid);
        writeFile(tmp.path("lock"), std::string(10 - owner.size(), ' ') + owner + "\n");
        writeFile(tmp.path("socket"), "");
        svo::app::setChildFiles(slot, tmp.path("lock").c_str(), tmp.path("socket").c_str());
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
    svo::app::releaseChild(child.slot);
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
    svo::app::cleanUpForExit(); // what the signal handler runs: SIGTERM, wait, reap
    EXPECT_EQ(waitpid(child.pid, nullptr, WNOHANG), -1); // already reaped by the clean-up
    EXPECT_FALSE(fs::exists(tmp.path("lock")));
    EXPECT_FALSE(fs::exists(tmp.path("socket")));
    EXPECT_FALSE(fs::exists(tmp.path("out.tmp")));
    svo::releaseTemporary(temporary);
    svo::app::releaseChild(child.slot);
}

TEST(ExitCleanup, AnInterruptEndsTheRunUntilItFinishesWithoutInterrupts)
{
    EXPECT_EQ(exitStatusOf([] { raise(SIGTERM); }), 143);
    EXPECT_EQ(exitStatusOf([] {
                  svo::finishWithoutInterrupts();
                  raise(SIGTERM);
                  raise(SIGINT);
              }),
              0);
    EXPECT_EQ(exitStatusOf([] {
                  svo::finishWithoutInterrupts();
                  svo::allowInterrupts(); // a commit that failed: interrupts count again
                  raise(SIGINT);
              }),
              130);
}

TEST(OutputBatch, NothingIsReplacedUntilTheCommitThenEverything)
{
    svo::test::TempDir tmp("output-batch");
    const std::string a = tmp.write("a.txt", "old a"), b = tmp.write("b.txt", "old b"), c = tmp.path("c.txt");
    {
        svo::OutputBatch batch({a, b});
        batch.add(c);
        svo::writeFileAtomically(a, "new a");
        svo::writeFileAtomically(c, "new c");
        EXPECT_EQ(readFile(a), "old a");
        EXPECT_FALSE(fs::exists(c));
        EXPECT_EQ(svo::outputBytes(a), 5u); // the waiting temporary's size
        svo::writeFileAtomically(b, "new b");
        batch.commit();
    }
    EXPECT_EQ(readFile(a), "new a");
    EXPECT_EQ(readFile(b), "new b");
    EXPECT_EQ(readFile(c), "new c");
    EXPECT_EQ(filesIn(tmp), 3u); // no temporary left
    // Without a batch, a write is in place at once.
    svo::writeFileAtomically(a, "newer a");
    EXPECT_EQ(readFile(a), "newer a");
}

TEST(OutputBatch, AFailureBeforeTheCommitLeavesEveryEarlierFile)
{
    svo::test::TempDir tmp("output-batch");
    const std::string a = tmp.write("a.txt", "old a"), b = tmp.write("b.txt", "old b");
    try {
        svo::OutputBatch batch({a, b});
        svo::writeFileAtomically(a, "new a");
        svo::writeAtomically(b, [](const std::string&) { throw svo::Error("disk full"); });
        batch.commit();
        FAIL() << "the second output's error was lost";
    } catch (const svo::Error& e) {
        EXPECT_NE(std::string(e.what()).find("disk full"), std::string::npos) << e.what();
    }
    EXPECT_EQ(readFile(a), "old a");
    EXPECT_EQ(readFile(b), "old b");
    EXPECT_EQ(filesIn(tmp), 2u);
}

TEST(OutputBatch, ACommitThatFailsHalfwaySaysWhatWasWritten)
{
    svo::test::TempDir tmp("output-batch");
    const std::string a = tmp.write("a.txt", "old a");
    fs::create_directory(tmp.path("sub"));
    const std::string b = tmp.path("sub/b.txt");
    try {
        svo::OutputBatch batch({a, b});
        svo::writeFileAtomically(a, "new a");
        svo::writeFileAtomically(b, "new b");
        // The folder goes before the commit: b's rename fails after a's.
        fs::remove_all(tmp.path("sub"));
        batch.commit();
        FAIL() << "the failed rename was not reported";
    } catch (const svo::Error& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find(b + ": cannot move the finished file into place"), std::string::npos) << m;
        EXPECT_NE(m.find("written: " + a), std::string::npos) << m;
        EXPECT_NE(m.find("not written: " + b), std::string::npos) << m;
    }
    EXPECT_EQ(readFile(a), "new a");
    EXPECT_EQ(filesIn(tmp), 1u);
    svo::allowInterrupts();
}
