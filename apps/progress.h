#pragma once
/// @file progress.h
/// A progress line on stderr for any step that runs longer than a second.
#include <atomic>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

namespace svo::app {

/// Shows "<label> ... 3.2 s" on stderr, refreshed 4 times a second, once the
/// step has run for one second; on a non-terminal it prints one line when the
/// step starts being slow and one when it ends. Quiet steps print nothing.
class Progress {
public:
    explicit Progress(std::string label);
    ~Progress();
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

private:
    void run();
    std::string label_;
    std::mutex mutex_;
    std::condition_variable cv_;
    bool done_ = false;
    std::thread thread_;
};

} // namespace svo::app
