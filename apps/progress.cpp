#include "progress.h"

#include <chrono>
#include <cstdio>
#include <fmt/format.h>
#include <unistd.h>

namespace svo::app {

Progress::Progress(std::string label) : label_(std::move(label)), thread_([this] { run(); }) {}

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
    const bool tty = ::isatty(STDERR_FILENO);
    std::unique_lock<std::mutex> lock(mutex_);
    if (cv_.wait_for(lock, seconds(1), [this] { return done_; })) return;
    if (!tty) fmt::print(stderr, "{} ...\n", label_);
    while (!cv_.wait_for(lock, milliseconds(250), [this] { return done_; })) {
        if (!tty) continue;
        const double s = duration<double>(steady_clock::now() - start).count(), f = fraction_.load();
        // The estimate assumes the rest goes at the pace so far; shown once 5 % is done.
        if (f >= 0.05 && f < 1.0)
            fmt::print(stderr, "\r{} ... {:.0f} %, {:.1f} s, about {:.0f} s left   ", label_, 100 * f, s,
                       s * (1 - f) / f);
        else if (f >= 0)
            fmt::print(stderr, "\r{} ... {:.0f} %, {:.1f} s   ", label_, 100 * f, s);
        else
            fmt::print(stderr, "\r{} ... {:.1f} s", label_, s);
    }
    const double s = duration<double>(steady_clock::now() - start).count();
    fmt::print(stderr, "{}{} {} {:.1f} s{}\n", tty ? "\r" : "", label_, failed_ ? "stopped after" : "done in", s,
               tty ? "                    " : "");
}

} // namespace svo::app
