#pragma once
/// @file exit_cleanup.h
/// What an interrupt must undo: temporary files that are not yet renamed into
/// place, and child processes svo started (the Xvfb server).
///
/// writeAtomically() registers its temporary here for as long as it exists
/// (in an OutputBatch, until the batch's commit), and app code registers the
/// children it starts. A program that wants
/// SIGINT and SIGTERM to leave nothing behind either calls
/// installInterruptCleanup() (the CLI does) or, from its own signal handler,
/// cleanUpForExit(). Both are safe inside a signal handler: the registry is a
/// fixed array of atomics and the clean-up uses only unlink, kill, waitpid,
/// nanosleep, and open, read and close.
///
/// Library callers that cancel through an interrupter need none of this: a
/// cancelled call unwinds by exception, and writeAtomically removes its
/// temporary on the way out.
#include <sys/types.h>

namespace svo {

/// Registers a temporary file path (copied) until the returned slot is
/// released. Returns -1 when the path is too long or the registry is full,
/// in which case an interrupt leaves that one file behind.
int registerTemporary(const char* path) noexcept;
void releaseTemporary(int slot) noexcept;

/// Registers a child process to be sent SIGTERM on an interrupt.
int registerChild(pid_t pid) noexcept;
/// Files a registered child should remove when it exits (an X server's lock
/// and socket): once it is reaped, by the clean-up or before releaseChild(),
/// both are removed if `lock` still exists and holds the child's pid as text.
/// Paths are copied; over-long ones are ignored.
void setChildFiles(int slot, const char* lock, const char* leftover) noexcept;
/// Call after reaping the child: removes its files as setChildFiles says.
void releaseChild(int slot) noexcept;

/// Removes every registered temporary and terminates every registered child
/// (SIGTERM, then waits up to 2 s for each). Async-signal-safe.
void cleanUpForExit() noexcept;

/// From here on SIGINT and SIGTERM no longer stop the process: the handler
/// installed below returns at once, so that a run committing its outputs
/// (OutputBatch::commit in atomic_file.h) replaces all of them and exits as
/// it would have. Works for every thread, unlike a signal mask. If an
/// interrupt's clean-up has already begun, this never returns (the handler
/// exits). allowInterrupts() undoes it (a commit that failed).
void finishWithoutInterrupts() noexcept;
void allowInterrupts() noexcept;

/// Installs SIGINT and SIGTERM handlers that print "svo: interrupted" on
/// stderr, call cleanUpForExit() and exit with the conventional status, 128
/// plus the signal number (130 and 143).
void installInterruptCleanup();

} // namespace svo
