#pragma once
/// @file atomic_file.h
/// @brief Output files that appear whole or not at all, and the outputs of one
/// command that appear all together or not at all.
///
/// Where an output goes (outputTarget):
/// - a regular file, or a name that does not exist yet: replaced by a
///   temporary written beside it and renamed over it;
/// - a symbolic link: followed, so the file it names is replaced and the link
///   stays (as `cp` and the shell's `>` do); a dangling link creates its target;
/// - a character device or a FIFO (`/dev/null`, `/dev/stdout` on a terminal or
///   a pipe, a named pipe), or the file svo's standard output or error already
///   writes to (`/dev/stdout` redirected to a file): written through, never
///   replaced, once the whole output is finished in a temporary;
/// - a folder, a block device or a socket: refused (svo::IoError, one line).
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace svo {

/// @brief Fails early, before any heavy work, if @a path cannot be written.
/// @throw svo::IoError when it is empty, names a folder, a block device or a
///        socket, or its folder (of the file a link names) is missing or not
///        writable
void checkWritable(const std::string& path);

/// @brief Calls @a write with a temporary path, then moves the finished
/// temporary into place as the file comment says. If @a write throws or the
/// move fails, the temporary is removed and any earlier file at @a path is
/// left untouched. While an OutputBatch that holds @a path lives, the
/// finished temporary waits for its commit().
/// @param write writes the whole output to the path it is given
/// @throw svo::IoError naming @a path when it cannot be written (as
///        checkWritable) or the move fails, or for a std::exception from
///        @a write; an svo::Error from @a write passes through as it is
void writeAtomically(const std::string& path, const std::function<void(const std::string& tmp)>& write);

/// @brief Whether the two paths name one file: the same device and inode when
/// both exist (so symbolic and hard links count), the same resolved path
/// otherwise (`./`, `..` and linked folders resolved). Empty paths name no
/// file. Throws nothing.
bool sameFile(const std::string& a, const std::string& b);

/// @brief writeAtomically for bytes already in memory (text or binary).
/// @throw svo::IoError naming @a path, as writeAtomically
void writeFileAtomically(const std::string& path, const std::string& bytes);

/// @brief The size of the output just written to @a path: its temporary
/// while it waits in an OutputBatch, else the file.
/// @return bytes; 0 when there is no file, as for an output written through
///         a device
uint64_t outputBytes(const std::string& path);

/// @brief The outputs of one command, committed together: a run replaces all of
/// them or none. While a batch lives (one at a time in a process),
/// writeAtomically() to one of its paths finishes the temporary and leaves it
/// (registered with pending_files.h, so an interrupt removes it); commit()
/// then moves them all into place. Destroyed without a commit (an error
/// unwinding), it removes every temporary and no earlier file is touched.
/// Writes to other paths (a program cache) are not held back.
class OutputBatch {
public:
    /// @brief Starts holding back writes to @a paths (empty paths are ignored).
    /// @throw std::logic_error while another batch lives in the process
    explicit OutputBatch(const std::vector<std::string>& paths = {});
    /// @brief Without a commit, removes every temporary; never throws.
    ~OutputBatch();
    OutputBatch(const OutputBatch&) = delete;
    OutputBatch& operator=(const OutputBatch&) = delete;

    /// @brief Holds back writes to @a path too (empty paths are ignored).
    void add(const std::string& path);

    /// @brief Puts every held output in place. Writes the outputs that go
    /// through a device first (nothing is replaced
    /// yet, and an interrupt still removes every temporary), then renames the
    /// others into place with interrupts deferred (finishWithoutInterrupts in
    /// pending_files.h; a flag the handler reads, since a signal mask covers
    /// one thread only). From then on the run has done what it was asked, and
    /// a SIGINT or SIGTERM no longer turns it into a failure.
    /// @throw svo::IoError naming the output that failed and those that were
    ///        already written; the remaining temporaries are removed and
    ///        interrupts are allowed again
    void commit();

private:
    struct Impl; // atomic_file.cpp's: the paths held back and the outputs staged
    Impl* impl_;
};

} // namespace svo
