// threads.hpp - the one thread splitter of both extension modules (_core's
// row-wise tests and accumulator arrays, _estimators' batches).
//
// Work on [0, n) is split into contiguous ranges, one per thread.  Every
// caller's work is a pure function of the index (a row, an estimate drawn
// from (seed, index)), so results never depend on the number of threads or
// on where the ranges split; only the cost does.  Starting a thread costs
// about 30 us, so each caller gives the least work per thread that pays for
// one (min_per_thread).
//
// Header-only and free of Python: call it without the GIL; f must not touch
// Python objects.
//
// Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
#pragma once

#include <cstddef>
#include <system_error>
#include <thread>
#include <vector>

namespace mcs_threads {

// Runs f(begin, end) -> int status over [0, n) in at most `threads`
// contiguous ranges of at least min_per_thread items (one range, on the
// calling thread, when n < 2 min_per_thread).  Returns the status of the
// first failing range in index order, 0 when all succeeded.  A thread that
// cannot be started runs its range on the calling thread instead (the same
// numbers, later).
template <typename F> int split_ranges(std::size_t n, std::size_t threads, std::size_t min_per_thread, F f)
{
    std::size_t T = min_per_thread ? n / min_per_thread : n;
    if (T > threads)
        T = threads;
    if (T <= 1)
        return f(std::size_t{0}, n);
    std::vector<int> status(T, 0);
    std::vector<std::thread> pool;
    pool.reserve(T - 1);
    for (std::size_t t = 1; t < T; t++) {
        std::size_t b = n * t / T, e = n * (t + 1) / T;
        try {
            pool.emplace_back([&f, &status, t, b, e] { status[t] = f(b, e); });
        } catch (const std::system_error &) {
            status[t] = f(b, e);
        }
    }
    status[0] = f(std::size_t{0}, n / T);
    for (auto &th : pool)
        th.join();
    for (int s : status)
        if (s)
            return s;
    return 0;
}

} // namespace mcs_threads
