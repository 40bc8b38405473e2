#pragma once
/// @file xvfb.h
/// An X display for offscreen VTK rendering: the current one, or a private
/// Xvfb server started for as long as this object lives.
#include <string>
#include <sys/types.h>

namespace svo::app {

/// Throws the error XDisplay would, without starting anything: for checking
/// before long work (a DISPLAY that does not open, with no Xvfb to stand in).
void requireDisplay();

class XDisplay {
public:
    /// Uses $DISPLAY when it opens; otherwise (unset, or no server there, with
    /// a warning) starts Xvfb on a free display and sets $DISPLAY. Throws
    /// svo::Error in one line saying what to do when neither works. The
    /// server dies with svo, even with svo killed by SIGKILL.
    XDisplay();
    ~XDisplay();
    XDisplay(const XDisplay&) = delete;
    XDisplay& operator=(const XDisplay&) = delete;
    const std::string& name() const { return name_; }
    bool started() const { return pid_ > 0; }

private:
    std::string name_;
    pid_t pid_ = -1;
    int cleanupSlot_ = -1; ///< interrupt_cleanup.h: an interrupt stops the server too
    std::string previous_; ///< a DISPLAY that did not open, restored afterwards
};

} // namespace svo::app
