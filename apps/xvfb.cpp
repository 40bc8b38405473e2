#include "xvfb.h"

#include <csignal>
#include <cstdlib>
#include <fcntl.h>
#include <fmt/format.h>
#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

#include "svo/core/error.h"
#include "svo/core/exit_cleanup.h"

namespace svo::app {
namespace {

bool onPath(const char* exe)
{
    const char* path = std::getenv("PATH");
    std::string dirs = path ? path : "/usr/bin:/bin";
    size_t start = 0;
    while (start <= dirs.size()) {
        const size_t end = dirs.find(':', start);
        const std::string dir = dirs.substr(start, end == std::string::npos ? std::string::npos : end - start);
        if (!dir.empty() && ::access((dir + "/" + exe).c_str(), X_OK) == 0) return true;
        if (end == std::string::npos) break;
        start = end + 1;
    }
    return false;
}

} // namespace

void requireDisplay()
{
    if (const char* d = std::getenv("DISPLAY"); d && *d) return;
    if (!onPath("Xvfb"))
        throw Error("rendering a picture needs an X display: Debian's VTK 9.1 has no EGL or OSMesa backend. Set "
                    "DISPLAY, or install Xvfb (apt-get install xvfb) and svo starts one itself");
}

XDisplay::XDisplay()
{
    requireDisplay();
    if (const char* d = std::getenv("DISPLAY"); d && *d) {
        name_ = d;
        return;
    }
    int fds[2];
    if (::pipe(fds) != 0) throw Error("cannot create a pipe to start Xvfb");
    pid_ = ::fork();
    if (pid_ < 0) throw Error("cannot start Xvfb (fork failed)");
    if (pid_ == 0) {
        ::close(fds[0]);
        const int devnull = ::open("/dev/null", O_WRONLY);
        if (devnull >= 0) ::dup2(devnull, 2), ::dup2(devnull, 1);
        const std::string fd = std::to_string(fds[1]);
        ::execlp("Xvfb", "Xvfb", "-displayfd", fd.c_str(), "-screen", "0", "1920x1080x24", "-nolisten", "tcp",
                 static_cast<char*>(nullptr));
        ::_exit(127);
    }
    ::close(fds[1]);
    cleanupSlot_ = registerChild(pid_);
    // Xvfb writes its display number to the pipe once it accepts connections.
    std::string number;
    pollfd p{fds[0], POLLIN, 0};
    char c;
    while (::poll(&p, 1, 10000) > 0 && ::read(fds[0], &c, 1) == 1 && c != '\n') number += c;
    ::close(fds[0]);
    if (number.empty()) {
        ::kill(pid_, SIGTERM);
        ::waitpid(pid_, nullptr, 0);
        releaseChild(cleanupSlot_);
        pid_ = -1;
        throw Error("Xvfb did not start within 10 s; set DISPLAY to an X server instead");
    }
    name_ = ":" + number;
    // Removed after the server exits if it left them (see setChildFiles).
    setChildFiles(cleanupSlot_, ("/tmp/.X" + number + "-lock").c_str(), ("/tmp/.X11-unix/X" + number).c_str());
    ::setenv("DISPLAY", name_.c_str(), 1);
}

XDisplay::~XDisplay()
{
    if (pid_ <= 0) return;
    ::kill(pid_, SIGTERM);
    ::waitpid(pid_, nullptr, 0);
    releaseChild(cleanupSlot_);
    ::unsetenv("DISPLAY");
}

} // namespace svo::app
