#pragma once
/// @file slot_table.h
/// @brief svo::SlotTable: a fixed table of entries that threads add and
/// remove and a signal handler walks, for what an interrupt must undo (the
/// temporaries of pending_files.h, the CLI's child processes).
///
/// Safe inside a signal handler: no allocation and no lock, only a lock-free
/// atomic state per slot. A slot's entry is written while the slot is taken
/// but not yet ready, so a handler never sees one half written.
#include <atomic>

namespace svo {

/// @brief @a Slots entries of type @a Entry (plain data and atomics: paths
/// as char arrays, pids), each free, being written, or ready.
template <typename Entry, int Slots = 64>
class SlotTable {
    static_assert(std::atomic<int>::is_always_lock_free, "a signal handler may only use lock-free atomics");

public:
    /// @brief Takes a free slot, lets @a fill write its entry, then makes it
    /// ready for forEachReady. Async-signal-safe when @a fill is.
    /// @return the slot, or -1 when every slot is taken
    template <typename Fill>
    int add(Fill&& fill) noexcept
    {
        for (int i = 0; i < Slots; ++i) {
            int expected = kFree;
            if (!slots_[i].state.compare_exchange_strong(expected, kWriting)) continue;
            fill(slots_[i].entry);
            slots_[i].state.store(kReady);
            return i;
        }
        return -1;
    }

    /// @brief The entry of a slot add() returned, to change what a handler
    /// will read of it; null for -1 or any other slot out of range.
    Entry* find(int slot) noexcept { return slot >= 0 && slot < Slots ? &slots_[slot].entry : nullptr; }

    /// @brief Frees a slot add() returned (-1 is ignored). Async-signal-safe.
    void remove(int slot) noexcept
    {
        if (slot >= 0 && slot < Slots) slots_[slot].state.store(kFree);
    }

    /// @brief Calls @a visit(entry) for each ready slot. Async-signal-safe
    /// when @a visit is.
    template <typename Visit>
    void forEachReady(Visit&& visit) noexcept
    {
        for (Slot& s : slots_)
            if (s.state.load() == kReady) visit(s.entry);
    }

private:
    enum : int { kFree = 0, kWriting = 1, kReady = 2 };
    struct Slot {
        std::atomic<int> state{kFree};
        Entry entry;
    };
    Slot slots_[Slots];
};

} // namespace svo
