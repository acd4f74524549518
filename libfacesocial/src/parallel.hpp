// The library's one threading backend (TBB) behind a small interface.
#pragma once

#include <cstddef>
#include <functional>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace facesocial::detail {

/// Calls fn(i) for i in [0, n) on up to `num_threads` threads (-1 = all cores, 1 = inline).
template <class Fn>
void parallel_for(std::size_t n, Fn&& fn, int num_threads = -1) {
    if (n == 0) return;
    if (num_threads == 1 || n == 1) {
        for (std::size_t i = 0; i < n; ++i) fn(i);
        return;
    }
    auto body = [&] {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1), [&](const tbb::blocked_range<std::size_t>& r) {
            for (std::size_t i = r.begin(); i != r.end(); ++i) fn(i);
        });
    };
    if (num_threads <= 0) {
        body();
    } else {
        tbb::task_arena arena(num_threads);
        arena.execute(body);
    }
}

}  // namespace facesocial::detail
