#include "svo/core/atomic_file.h"

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <mutex>
#include <random>
#include <sys/stat.h>
#include <unistd.h>

#include "svo/core/error.h"
#include "svo/core/pending_files.h"

namespace svo {
namespace fs = std::filesystem;

namespace {

/// Where an output goes (the header's list).
struct Target {
    bool through = false; ///< written through (a device, a FIFO, a standard stream), never replaced
    std::string file;     ///< replaced: the file renamed over (links followed); through: the path opened
    int fd = -1;          ///< through one of svo's own standard streams (1 or 2)
};

bool sameAsStream(const struct stat& st, int fd)
{
    struct stat s {};
    return ::fstat(fd, &s) == 0 && s.st_dev == st.st_dev && s.st_ino == st.st_ino;
}

/// `path` with symbolic links followed as far as they go, also to a name that
/// does not exist yet (a dangling link's target).
std::string followLinks(const std::string& path)
{
    fs::path p = path;
    for (int i = 0; i < 40; ++i) {
        struct stat st {};
        if (::lstat(p.c_str(), &st) != 0 || !S_ISLNK(st.st_mode)) return p.string();
        std::error_code ec;
        const fs::path to = fs::read_symlink(p, ec);
        if (ec) return p.string();
        p = to.is_absolute() ? to : p.parent_path() / to;
    }
    throw IoError(fmt::format("{}: too many levels of symbolic links", path));
}

Target outputTarget(const std::string& path)
{
    if (path.empty()) throw IoError("the output path is empty");
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) {
        if (errno == ELOOP) throw IoError(fmt::format("{}: too many levels of symbolic links", path));
        return {false, followLinks(path), -1}; // a new file (or a dangling link's target)
    }
    if (S_ISDIR(st.st_mode)) throw IoError(fmt::format("{}: is a folder; give a file name", path));
    struct stat link {};
    const bool named = ::lstat(path.c_str(), &link) == 0 && S_ISLNK(link.st_mode);
    // /dev/stdout and /dev/stderr (terminal, pipe, or a file the shell opened): through the stream itself,
    // after what svo printed there; a regular file named directly is replaced even if it is also stdout.
    if (named || !S_ISREG(st.st_mode))
        for (const int fd : {STDOUT_FILENO, STDERR_FILENO})
            if (sameAsStream(st, fd)) return {true, path, fd};
    if (S_ISREG(st.st_mode)) {
        char* real = ::realpath(path.c_str(), nullptr);
        const std::string file = real ? real : followLinks(path);
        std::free(real);
        return {false, file, -1};
    }
    if (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode)) return {true, path, -1};
    throw IoError(fmt::format("{}: is {}; svo replaces regular files and writes through character devices and FIFOs, "
                              "and leaves anything else alone",
                              path, S_ISBLK(st.st_mode) ? "a block device" : S_ISSOCK(st.st_mode) ? "a socket" : "not a file"));
}

void checkTarget(const std::string& path, const Target& t)
{
    std::error_code ec;
    if (t.through) {
        if (t.fd < 0 && ::access(t.file.c_str(), W_OK) != 0)
            throw IoError(fmt::format("{}: cannot be written: {}", path, std::strerror(errno)));
        const fs::path dir = fs::temp_directory_path(ec);
        if (ec || ::access(dir.c_str(), W_OK) != 0)
            throw IoError(fmt::format("{}: needs a temporary file first, and the temporary folder {} is not writable "
                                      "(set TMPDIR)",
                                      path, dir.string()));
        return;
    }
    const fs::path p(t.file);
    const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
    if (!fs::is_directory(dir, ec)) throw IoError(fmt::format("{}: the folder {} does not exist", path, dir.string()));
    if (::access(dir.c_str(), W_OK) != 0)
        throw IoError(fmt::format("{}: the folder {} is not writable", path, dir.string()));
}

std::string temporaryFor(const Target& t)
{
    std::random_device rd;
    if (!t.through) return fmt::format("{}.tmp-{:08x}", t.file, rd());
    std::error_code ec;
    return (fs::temp_directory_path(ec) / fmt::format("svo-output-{}.tmp-{:08x}", ::getpid(), rd())).string();
}

/// Copies the finished temporary into a device, a FIFO (waiting for a reader)
/// or a standard stream. SIGPIPE is ignored meanwhile: a reader that went away
/// is an error (EPIPE) like any other.
void writeThrough(const std::string& path, const Target& t, const std::string& tmp)
{
    const int in = ::open(tmp.c_str(), O_RDONLY | O_CLOEXEC);
    if (in < 0) throw IoError(fmt::format("{}: cannot read the finished temporary {}: {}", path, tmp, std::strerror(errno)));
    int out = t.fd;
    if (out == STDOUT_FILENO) std::fflush(stdout);
    if (out == STDERR_FILENO) std::fflush(stderr);
    if (out < 0) {
        do out = ::open(t.file.c_str(), O_WRONLY | O_CLOEXEC | O_NOCTTY);
        while (out < 0 && errno == EINTR);
    }
    int error = out < 0 ? errno : 0;
    struct sigaction ignore {}, previous {};
    ignore.sa_handler = SIG_IGN;
    sigemptyset(&ignore.sa_mask);
    ::sigaction(SIGPIPE, &ignore, &previous);
    char buffer[1 << 16];
    while (!error) {
        const ssize_t n = ::read(in, buffer, sizeof buffer);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            if (n < 0) error = errno;
            break;
        }
        for (ssize_t done = 0; done < n && !error;) {
            const ssize_t w = ::write(out, buffer + done, size_t(n - done));
            if (w < 0 && errno != EINTR) error = errno;
            if (w > 0) done += w;
        }
    }
    ::sigaction(SIGPIPE, &previous, nullptr);
    if (out >= 0 && t.fd < 0) ::close(out);
    ::close(in);
    if (error) throw IoError(fmt::format("{}: cannot write: {}", path, std::strerror(error)));
}

/// Puts a finished temporary in place; removes it either way.
void deliver(const std::string& path, const Target& t, const std::string& tmp)
{
    if (t.through) {
        try {
            writeThrough(path, t, tmp);
        } catch (...) {
            std::remove(tmp.c_str());
            throw;
        }
        std::remove(tmp.c_str());
        return;
    }
    std::error_code ec;
    fs::rename(tmp, t.file, ec);
    if (ec) {
        std::remove(tmp.c_str());
        throw IoError(fmt::format("{}: cannot move the finished file into place: {}", path, ec.message()));
    }
}

/// Tests only: SVO_TEST_SIGNAL=staged:N raises SIGTERM once the Nth output of
/// a batch is finished and waits for its commit, renamed:N once the commit has
/// renamed N outputs: an interrupt at exactly those points.
void testSignal(const char* event, size_t count)
{
    const char* spec = std::getenv("SVO_TEST_SIGNAL");
    if (spec && fmt::format("{}:{}", event, count) == spec) ::raise(SIGTERM);
}

struct Staged {
    std::string path, tmp;
    Target target;
    int slot;
};

/// What a live OutputBatch holds, where writeAtomically finds it.
struct Batch {
    std::vector<std::string> paths;
    std::vector<Staged> staged;
};

std::mutex batchMutex;
Batch* activeBatch = nullptr; // guarded by batchMutex

void discard(Staged& s)
{
    std::remove(s.tmp.c_str());
    releaseTemporary(s.slot);
}

} // namespace

// OutputBatch's private Impl is a Batch, which the free functions above can
// name (a private nested type they could not).
struct OutputBatch::Impl : Batch {};

void checkWritable(const std::string& path)
{
    checkTarget(path, outputTarget(path));
}

void writeAtomically(const std::string& path, const std::function<void(const std::string& tmp)>& write)
{
    const Target target = outputTarget(path);
    checkTarget(path, target);
    const std::string tmp = temporaryFor(target);
    // Registered before it exists, so that an interrupt at any point removes it.
    const int slot = registerTemporary(tmp.c_str());
    try {
        write(tmp);
    } catch (const Error&) {
        std::remove(tmp.c_str());
        releaseTemporary(slot);
        throw;
    } catch (const std::exception& e) {
        std::remove(tmp.c_str());
        releaseTemporary(slot);
        throw IoError(fmt::format("{}: cannot write the file: {}", path, e.what()));
    }
    {
        std::unique_lock<std::mutex> lock(batchMutex);
        if (activeBatch && std::count(activeBatch->paths.begin(), activeBatch->paths.end(), path)) {
            auto& staged = activeBatch->staged;
            for (auto it = staged.begin(); it != staged.end(); ++it)
                if (it->path == path) { // written twice: the later one counts
                    discard(*it);
                    staged.erase(it);
                    break;
                }
            staged.push_back({path, tmp, target, slot});
            const size_t n = staged.size();
            lock.unlock();
            testSignal("staged", n);
            return;
        }
    }
    try {
        deliver(path, target, tmp);
    } catch (...) {
        releaseTemporary(slot);
        throw;
    }
    releaseTemporary(slot);
}

bool sameFile(const std::string& a, const std::string& b)
{
    if (a.empty() || b.empty()) return false;
    std::error_code ec;
    if (std::filesystem::exists(a, ec) && std::filesystem::exists(b, ec))
        return std::filesystem::equivalent(a, b, ec);
    return std::filesystem::weakly_canonical(a, ec) == std::filesystem::weakly_canonical(b, ec);
}

void writeFileAtomically(const std::string& path, const std::string& bytes)
{
    // POSIX calls rather than a stream, so that a full disk is named (errno).
    writeAtomically(path, [&](const std::string& tmp) {
        const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
        if (fd < 0) throw IoError(fmt::format("{}: cannot write the file: {}", path, std::strerror(errno)));
        size_t done = 0;
        int error = 0;
        while (done < bytes.size() && !error) {
            const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
            if (n > 0) done += size_t(n);
            else if (n == 0) error = EIO;
            else if (errno != EINTR) error = errno;
        }
        if (::close(fd) != 0 && !error) error = errno;
        if (error) throw IoError(fmt::format("{}: cannot write the file: {}", path, std::strerror(error)));
    });
}

uint64_t outputBytes(const std::string& path)
{
    std::string file = path;
    {
        const std::lock_guard<std::mutex> lock(batchMutex);
        if (activeBatch)
            for (const auto& s : activeBatch->staged)
                if (s.path == path) file = s.tmp;
    }
    std::error_code ec;
    const auto size = fs::file_size(file, ec);
    return ec ? 0 : uint64_t(size);
}

OutputBatch::OutputBatch(const std::vector<std::string>& paths) : impl_(new Impl)
{
    const std::lock_guard<std::mutex> lock(batchMutex);
    if (activeBatch) {
        delete impl_;
        throw std::logic_error("svo::OutputBatch: one batch at a time");
    }
    for (const auto& p : paths)
        if (!p.empty()) impl_->paths.push_back(p);
    activeBatch = impl_;
}

OutputBatch::~OutputBatch()
{
    const std::lock_guard<std::mutex> lock(batchMutex);
    for (auto& s : impl_->staged) discard(s);
    if (activeBatch == impl_) activeBatch = nullptr;
    delete impl_;
}

void OutputBatch::add(const std::string& path)
{
    const std::lock_guard<std::mutex> lock(batchMutex);
    if (!path.empty()) impl_->paths.push_back(path);
}

void OutputBatch::commit()
{
    std::vector<Staged> staged;
    {
        const std::lock_guard<std::mutex> lock(batchMutex);
        staged.swap(impl_->staged);
        activeBatch = nullptr; // later writes go straight to their place
    }
    std::vector<std::string> written;
    size_t next = 0; // staged[next..] still waits
    auto fail = [&](const std::string& why) {
        for (size_t i = next; i < staged.size(); ++i) discard(staged[i]);
        std::string message = why;
        auto list = [](const std::vector<std::string>& names) {
            std::string text;
            for (const auto& n : names) text += (text.empty() ? "" : ", ") + n;
            return text;
        };
        std::vector<std::string> rest;
        for (size_t i = next; i < staged.size(); ++i) rest.push_back(staged[i].path);
        message += written.empty() ? "; no output was written" : "; written: " + list(written);
        if (!rest.empty()) message += "; not written: " + list(rest);
        throw IoError(message);
    };
    // Devices and FIFOs first: nothing is replaced yet, and a reader that
    // never comes can still be interrupted.
    std::stable_partition(staged.begin(), staged.end(), [](const Staged& s) { return s.target.through; });
    for (; next < staged.size() && staged[next].target.through; ++next) {
        Staged& s = staged[next];
        try {
            writeThrough(s.path, s.target, s.tmp);
        } catch (const Error& e) {
            fail(e.what());
        }
        discard(s);
        written.push_back(s.path);
    }
    // Then the renames, which an interrupt no longer stops halfway.
    finishWithoutInterrupts();
    size_t renamed = 0;
    for (; next < staged.size(); ++next) {
        Staged& s = staged[next];
        std::error_code ec;
        fs::rename(s.tmp, s.target.file, ec);
        if (ec) {
            allowInterrupts();
            fail(fmt::format("{}: cannot move the finished file into place: {}", s.path, ec.message()));
        }
        releaseTemporary(s.slot);
        written.push_back(s.path);
        testSignal("renamed", ++renamed);
    }
}

} // namespace svo
