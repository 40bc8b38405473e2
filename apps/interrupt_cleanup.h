#pragma once
/// @file interrupt_cleanup.h
/// What an interrupt of the svo tool must undo: the temporary files the
/// library has not yet renamed into place (svo/core/pending_files.h) and the
/// child processes svo started (the Xvfb server).
///
/// installInterruptCleanup() installs SIGINT and SIGTERM handlers that do
/// both and exit; cleanUpForExit() is the same clean-up for a program with a
/// handler of its own. Both are safe inside a signal handler: the registry is
/// a fixed table of atomic slots (svo/core/slot_table.h, as the library's
/// temporaries) and the clean-up uses only unlink, kill, waitpid, nanosleep,
/// and open, read and close.
#include <sys/types.h>

namespace svo::app {

/// @brief Registers a child process to be sent SIGTERM on an interrupt.
/// @return its slot, or -1 when the registry is full
int registerChild(pid_t pid) noexcept;
/// @brief Files a registered child should remove when it exits (an X server's
/// lock and socket): once it is reaped, by the clean-up or before
/// releaseChild(), both are removed if @a lock still exists and holds the
/// child's pid as text. Paths are copied; over-long ones are ignored.
void setChildFiles(int slot, const char* lock, const char* leftover) noexcept;
/// @brief Call after reaping the child: removes its files as setChildFiles says.
void releaseChild(int slot) noexcept;

/// @brief Removes every registered temporary and terminates every registered
/// child (SIGTERM, then waits up to 2 s for each). Async-signal-safe.
void cleanUpForExit() noexcept;

/// @brief Installs SIGINT and SIGTERM handlers that print "svo: interrupted"
/// on stderr, call cleanUpForExit() and exit with the conventional status,
/// 128 plus the signal number (130 and 143). While the outputs are being
/// committed (svo::finishWithoutInterrupts) they return instead.
void installInterruptCleanup();

} // namespace svo::app
