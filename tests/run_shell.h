#pragma once
/// @file run_shell.h
/// The tests' way to run a shell command and keep what it printed.
#include <array>
#include <cstdio>
#include <string>
#include <sys/wait.h>

namespace svo::test {

struct Run {
    int code; ///< the exit status, -1 when killed by a signal
    std::string out;
};

/// A shell command's exit status and output (stdout and stderr).
inline Run runShell(const std::string& command)
{
    FILE* p = popen((command + " 2>&1").c_str(), "r");
    std::string out;
    std::array<char, 4096> buf;
    size_t n;
    while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) out.append(buf.data(), n);
    const int status = pclose(p);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

} // namespace svo::test
