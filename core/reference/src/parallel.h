#pragma once
// Runs f on TBB's default arena, or on one of `threads` threads; the
// reference's results never depend on which.
#include <tbb/task_arena.h>

namespace svo::reference {

template <typename F>
void inArena(int threads, F&& f)
{
    if (threads <= 0) {
        f();
        return;
    }
    tbb::task_arena arena(threads);
    arena.execute(f);
}

} // namespace svo::reference
