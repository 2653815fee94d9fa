// output_array.hpp - NumPy arrays for the extension's image-scale outputs.
//
// An output of an image test is fresh memory, first touched by the C
// kernel's writes; with 4 KiB pages those page faults cost as much as a
// fast kernel itself (perf of the per-pixel test at 1920x1080: the
// operating system clearing new pages at 32% of the call's CPU time).  So
// a large output is allocated on 2 MiB boundaries and Linux is asked for
// transparent huge pages there, 512 times fewer faults.  An advice: where
// it is refused, or off Linux, the memory is as usual; small arrays are
// NumPy's own.
//
// Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
#pragma once

#include <pybind11/numpy.h>

#include <cstdlib>
#include <new>
#include <vector>
#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace mcs {

template <typename T> pybind11::array_t<T> output_array(const std::vector<pybind11::ssize_t> &shape)
{
    size_t n = 1;
    for (pybind11::ssize_t s : shape)
        n *= static_cast<size_t>(s);
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    const size_t huge = size_t(2) << 20;
    if (n * sizeof(T) >= 2 * huge) { // the rounding up costs at most half
        size_t bytes = (n * sizeof(T) + huge - 1) & ~(huge - 1);
        void *m = std::aligned_alloc(huge, bytes);
        if (!m)
            throw std::bad_alloc();
        madvise(m, bytes, MADV_HUGEPAGE);
        pybind11::capsule owner(m, [](void *q) { std::free(q); });
        return pybind11::array_t<T>(shape, static_cast<T *>(m), owner);
    }
#endif
    return pybind11::array_t<T>(shape);
}

} // namespace mcs
