#include "progress.h"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <fmt/format.h>
#include <unistd.h>

namespace svo::app {
namespace {
std::atomic<bool> progressShown{true};
} // namespace

void setProgressShown(bool shown) { progressShown.store(shown); }

Progress::Progress(std::string label, ProgressTiming timing)
    : label_(std::move(label)), timing_(timing), thread_([this] { run(); })
{
}

Progress::~Progress()
{
    {
        std::lock_guard<std::mutex> lock(mutex_);
        done_ = true;
        failed_ = std::uncaught_exceptions() > exceptions_;
    }
    cv_.notify_all();
    thread_.join();
}

void Progress::run()
{
    using namespace std::chrono;
    const auto start = steady_clock::now();
    std::FILE* out = timing_.out;
    const bool tty = timing_.terminal >= 0 ? timing_.terminal == 1 : ::isatty(::fileno(out));
    // What has been done so far, in the words of one line.
    auto state = [&] {
        const double s = duration<double>(steady_clock::now() - start).count(), f = fraction_.load();
        // The estimate assumes the rest goes at the pace so far; shown once 5 % is done.
        if (f >= 0.05 && f < 1.0)
            return fmt::format("{} ... {:.0f} %, {:.1f} s, about {:.0f} s left", label_, 100 * f, s, s * (1 - f) / f);
        if (f >= 0) return fmt::format("{} ... {:.0f} %, {:.1f} s", label_, 100 * f, s);
        return fmt::format("{} ... {:.1f} s", label_, s);
    };
    if (!progressShown.load()) return;
    std::unique_lock<std::mutex> lock(mutex_);
    if (cv_.wait_for(lock, timing_.slowAfter, [this] { return done_; })) return;
    if (!tty) {
        // A log gets whole lines, each on its own: one now and one every logEvery.
        fmt::print(out, "{} ...\n", label_);
        std::fflush(out);
        while (!cv_.wait_for(lock, timing_.logEvery, [this] { return done_; })) {
            fmt::print(out, "{}\n", state());
            std::fflush(out);
        }
    } else {
        while (!cv_.wait_for(lock, timing_.refresh, [this] { return done_; })) {
            fmt::print(out, "\r{}   ", state());
            std::fflush(out);
        }
    }
    const double s = duration<double>(steady_clock::now() - start).count();
    fmt::print(out, "{}{} {} {:.1f} s{}\n", tty ? "\r" : "", label_, failed_ ? "stopped after" : "done in", s,
               tty ? "                    " : "");
    std::fflush(out);
}

} // namespace svo::app
