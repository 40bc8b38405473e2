#include "xvfb.h"

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <dlfcn.h>
#include <fcntl.h>
#include <fmt/format.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include "svo/core/error.h"
#include "interrupt_cleanup.h"

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

/// $DISPLAY, or empty.
std::string displayVariable()
{
    const char* d = std::getenv("DISPLAY");
    return d ? d : "";
}

/// Whether the X server `name` accepts a connection, asked as VTK will ask
/// it (libX11's XOpenDisplay, loaded here: svo links no X library). VTK
/// aborts the process with a page of log when it cannot open the display,
/// so this is checked first. libX11's own complaints (an authorization
/// refused) are kept off stderr. True when libX11 cannot be loaded: then
/// there is nothing to check with, and VTK has no X to abort on either.
bool displayOpens(const std::string& name)
{
    static void* x11 = ::dlopen("libX11.so.6", RTLD_NOW | RTLD_LOCAL); // kept: VTK loads it anyway
    if (!x11) return true;
    using Open = void* (*)(const char*);
    using Close = int (*)(void*);
    const auto open = reinterpret_cast<Open>(::dlsym(x11, "XOpenDisplay"));
    const auto close = reinterpret_cast<Close>(::dlsym(x11, "XCloseDisplay"));
    if (!open || !close) return true;
    std::fflush(stderr);
    const int saved = ::dup(STDERR_FILENO);
    const int devnull = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
    if (saved >= 0 && devnull >= 0) ::dup2(devnull, STDERR_FILENO);
    void* display = open(name.c_str());
    if (saved >= 0 && devnull >= 0) ::dup2(saved, STDERR_FILENO);
    if (devnull >= 0) ::close(devnull);
    if (saved >= 0) ::close(saved);
    if (display) close(display);
    return display != nullptr;
}

/// Whether svo must start its own server: no DISPLAY, or one that does not
/// open (then Xvfb stands in, with a warning). Throws, in one line, when it
/// must and cannot.
bool needXvfb()
{
    const std::string display = displayVariable();
    if (!display.empty() && displayOpens(display)) return false;
    if (onPath("Xvfb")) return true;
    if (display.empty())
        throw DeviceError("rendering a picture needs an X display: Debian's VTK 9.1 has no EGL or OSMesa backend. Set "
                          "DISPLAY, or install Xvfb (apt-get install xvfb) and svo starts one itself");
    throw DeviceError(fmt::format("rendering a picture needs an X display, and DISPLAY={} cannot be opened (no server "
                                  "there, or it refuses svo): start it, unset DISPLAY, or install Xvfb (apt-get install "
                                  "xvfb) and svo starts one itself",
                                  display));
}

} // namespace

void requireDisplay()
{
    needXvfb();
}

XDisplay::XDisplay()
{
    if (!needXvfb()) {
        name_ = displayVariable();
        return;
    }
    if (const std::string unusable = displayVariable(); !unusable.empty()) {
        fmt::print(stderr, "svo: warning: DISPLAY={} cannot be opened; rendering through an Xvfb server of svo's own\n",
                   unusable);
        previous_ = unusable;
    }
    const pid_t parent = ::getpid();
    int fds[2];
    if (::pipe(fds) != 0) throw DeviceError("cannot create a pipe to start Xvfb");
    pid_ = ::fork();
    if (pid_ < 0) throw DeviceError("cannot start Xvfb (fork failed)");
    if (pid_ == 0) {
        // The server dies with svo, even when svo is killed outright (SIGKILL)
        // and no clean-up runs: SIGTERM, on which Xvfb removes its lock and
        // socket. (The signal comes when the forking thread ends: XDisplay is
        // made on the thread that renders, which outlives it.) If svo died
        // before the request took hold, the server is not started at all.
        ::prctl(PR_SET_PDEATHSIG, SIGTERM);
        if (::getppid() != parent) ::_exit(127);
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
        throw DeviceError("Xvfb did not start within 10 s; set DISPLAY to an X server instead");
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
    if (previous_.empty())
        ::unsetenv("DISPLAY");
    else
        ::setenv("DISPLAY", previous_.c_str(), 1);
}

} // namespace svo::app
