#pragma once
/// @file progress.h
/// A progress line on stderr for any step that runs longer than a second.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <memory>
#include <exception>
#include <functional>
#include <mutex>
#include <openvdb/util/NullInterrupter.h>
#include <string>
#include <thread>

namespace svo::app {

/// Whether Progress lines are printed at all, in the whole process (on by
/// default; `svo -q` turns them off).
void setProgressShown(bool shown);

/// When a Progress speaks, and where.
struct ProgressTiming {
    std::chrono::milliseconds slowAfter{1000}; ///< a step is slow, and shown, after this long
    std::chrono::milliseconds refresh{250};    ///< a terminal's line is rewritten this often
    std::chrono::milliseconds logEvery{5000};  ///< elsewhere (a log), one line this often
    std::FILE* out = stderr;
    /// Whether `out` is a terminal: -1 asks isatty, 0 or 1 says (for tests).
    int terminal = -1;
};

/// Shows "<label> ... 42 %, 3.2 s, about 4 s left" once the step has run for
/// one second (the share and the estimate appear once set() has been
/// called). On a terminal the line is rewritten 4 times a second; elsewhere
/// (stderr to a log or a pipe) the step prints "<label> ..." when it becomes
/// slow, then one such line every 5 seconds, with no carriage returns.
/// Either way one line at the end says how long it took. Quiet steps print
/// nothing.
class Progress {
public:
    explicit Progress(std::string label, ProgressTiming timing = {});
    ~Progress();
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    /// The share of the step done, 0..1 (thread-safe).
    void set(double fraction) { fraction_.store(fraction); }

private:
    void run();
    std::string label_;
    ProgressTiming timing_;
    std::atomic<double> fraction_{-1.0};
    std::mutex mutex_;
    std::condition_variable cv_;
    bool done_ = false;
    bool failed_ = false; ///< the step ended by an exception: "stopped", not "done"
    int exceptions_ = std::uncaught_exceptions();
    std::thread thread_;
};

/// A Progress line for each step of a call that names its steps as it goes
/// (the validator's onStep): a step's line ends when the next starts, the
/// last one at finish() or when this ends.
class StepProgress {
public:
    /// What the call is to be told; valid while this object lives.
    std::function<void(const std::string&)> onStep()
    {
        return [this](const std::string& step) {
            current_.reset(); // the previous step's line ends first
            current_ = std::make_unique<Progress>(step);
        };
    }
    /// Ends the last step's line.
    void finish() { current_.reset(); }

private:
    std::unique_ptr<Progress> current_;
};

/// The library's interrupter, shown as a Progress line for each call.
class ProgressInterrupter : public openvdb::util::NullInterrupter {
public:
    explicit ProgressInterrupter(std::string label) : label_(std::move(label)) {}
    void start(const char*) override { progress_ = std::make_unique<Progress>(label_); }
    void end() override { progress_.reset(); }
    bool wasInterrupted(int percent) override
    {
        if (progress_ && percent >= 0) progress_->set(percent / 100.0);
        return false;
    }

private:
    std::string label_;
    std::unique_ptr<Progress> progress_;
};

} // namespace svo::app
