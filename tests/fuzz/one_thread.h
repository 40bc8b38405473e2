#pragma once
// Every fuzz target runs TBB on one thread. libFuzzer's coverage counters are
// not atomic: parallel loops would lose increments at random, so the corpus,
// and with it what a fixed seed finds, would change from run to run and from
// machine to machine. On one thread, CI replays exactly the run that passed
// here. The parallel readers still cut their input in pieces and join them.
#include <tbb/global_control.h>

inline const tbb::global_control fuzzOnOneThread(tbb::global_control::max_allowed_parallelism, 1);
