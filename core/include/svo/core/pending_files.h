#pragma once
/// @file pending_files.h
/// @brief Temporary files that are not yet renamed into place, for an
/// interrupt to remove, and the moment after which an interrupt no longer
/// ends a run (its outputs are being committed).
///
/// writeAtomically() registers its temporary here for as long as it exists
/// (in an OutputBatch, until the batch's commit). A program that wants SIGINT
/// and SIGTERM to leave nothing behind removes them from its signal handler
/// (the CLI's apps/interrupt_cleanup.h does). Everything here is safe inside
/// a signal handler: the registry is a fixed table of atomic slots
/// (slot_table.h), and removal uses only unlink.
///
/// Library callers that cancel through an interrupter need none of this: a
/// cancelled call unwinds by exception, and writeAtomically removes its
/// temporary on the way out.

namespace svo {

/// @brief Registers a temporary file path (copied) until its slot is released.
/// @return the slot, or -1 when the path is too long or the registry is full
///         (an interrupt then leaves that one file behind)
int registerTemporary(const char* path) noexcept;
/// @brief Releases a slot from registerTemporary (-1 is ignored).
void releaseTemporary(int slot) noexcept;
/// @brief Removes every registered temporary. Async-signal-safe.
void removeTemporaries() noexcept;

/// @brief From here on an interrupt no longer ends the run: a signal handler
/// that asks claimInterrupt() is told to return, so that a run committing its
/// outputs (OutputBatch::commit in atomic_file.h) replaces all of them and
/// exits as it would have. Works for every thread, unlike a signal mask.
/// @details If an interrupt's clean-up has already begun, this never returns
/// (the handler exits the process).
void finishWithoutInterrupts() noexcept;
/// @brief Undoes finishWithoutInterrupts() (a commit that failed).
void allowInterrupts() noexcept;
/// @brief The signal handler's side of finishWithoutInterrupts().
/// @return true when the interrupt ends the run (the caller cleans up and
///         exits); false when the outputs are being committed (the caller
///         returns). Never returns while another thread's handler cleans up.
bool claimInterrupt() noexcept;

} // namespace svo
