// The CLI's progress lines (apps/progress.h) with short intervals: a slow step
// written to a log (not a terminal) reports its share and time left in whole
// lines, one per interval, and a terminal's line is rewritten in place.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <gtest/gtest.h>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "progress.h"

namespace {

using namespace std::chrono_literals;

/// What a Progress wrote to `file`, from its start.
std::string readBack(std::FILE* file)
{
    std::fflush(file);
    std::rewind(file);
    std::string text;
    char buf[4096];
    for (size_t n; (n = std::fread(buf, 1, sizeof buf, file)) > 0;) text.append(buf, n);
    return text;
}

std::vector<std::string> linesOf(const std::string& text)
{
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    return lines;
}

/// A step slow after 50 ms, logged every 100 ms, that runs `ms` and sets its share on the way.
std::string slowStep(int terminal, int ms, bool setShare = true)
{
    std::FILE* file = std::tmpfile();
    EXPECT_NE(file, nullptr);
    {
        svo::app::ProgressTiming timing;
        timing.slowAfter = 50ms;
        timing.refresh = 20ms;
        timing.logEvery = 100ms;
        timing.out = file;
        timing.terminal = terminal;
        svo::app::Progress p("converting", timing);
        const auto start = std::chrono::steady_clock::now();
        while (std::chrono::steady_clock::now() - start < std::chrono::milliseconds(ms)) {
            if (setShare)
                p.set(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() / ms);
            std::this_thread::sleep_for(5ms);
        }
    }
    std::string text = readBack(file);
    std::fclose(file);
    return text;
}

} // namespace

TEST(Progress, LogGetsALineEveryIntervalWithShareAndTimeLeft)
{
    const std::string text = slowStep(0, 700);
    EXPECT_EQ(text.find('\r'), std::string::npos) << text;
    const auto lines = linesOf(text);
    ASSERT_GE(lines.size(), 5u) << text; // the start, at least 3 updates in 650 ms at 100 ms, the end
    EXPECT_EQ(lines.front(), "converting ...");
    EXPECT_EQ(lines.back().rfind("converting done in ", 0), 0u) << lines.back();
    int updates = 0;
    for (size_t i = 1; i + 1 < lines.size(); ++i) {
        EXPECT_EQ(lines[i].rfind("converting ... ", 0), 0u) << lines[i];
        EXPECT_NE(lines[i].find(" %, "), std::string::npos) << lines[i];
        updates += lines[i].find(" s left") != std::string::npos;
    }
    EXPECT_GE(updates, 3) << text;
    // One a interval, not one a refresh: 650 ms of 100 ms intervals.
    EXPECT_LE(lines.size(), 9u) << text;
}

TEST(Progress, LogWithoutAShareStillGetsTheTime)
{
    const auto lines = linesOf(slowStep(0, 400, false));
    ASSERT_GE(lines.size(), 3u);
    EXPECT_EQ(lines[1].rfind("converting ... ", 0), 0u) << lines[1];
    EXPECT_EQ(lines[1].find('%'), std::string::npos) << lines[1];
    EXPECT_EQ(lines[1].substr(lines[1].size() - 2), " s") << lines[1];
}

TEST(Progress, QuickStepPrintsNothing)
{
    EXPECT_EQ(slowStep(0, 10), "");
    EXPECT_EQ(slowStep(1, 10), "");
}

TEST(Progress, TerminalLineIsRewrittenInPlace)
{
    const std::string text = slowStep(1, 300);
    // One line in all: every update starts with a carriage return, and the end closes it.
    EXPECT_EQ(linesOf(text).size(), 1u) << text;
    EXPECT_GE(std::count(text.begin(), text.end(), '\r'), 5) << text;
    EXPECT_NE(text.find("\rconverting ... "), std::string::npos);
    EXPECT_NE(text.find("\rconverting done in "), std::string::npos);
    EXPECT_EQ(text.back(), '\n');
}
