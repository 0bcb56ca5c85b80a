// The barrier between the passes of one threaded step (cpu_solver.h Team, cpu_multigrid.h
// CycleThreads). Its threads meet thousands of times a second, usually a few microseconds
// apart: an arrival spins first (about 50 µs at most), then sleeps on the generation (a futex),
// so that a thread whose partner was descheduled does not hold its core. std::barrier sleeps
// almost at once: 9–14 µs a meeting of two threads on this project's machines, against 0.2–0.3
// µs spinning (docs/performance.md, "The passes' barrier").
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <utility>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace cloth {

class SpinBarrier {
public:
    // `completion` runs once a meeting, on the last thread to arrive, before any thread leaves.
    explicit SpinBarrier(int count, std::function<void()> completion = {})
        : count_(count), completion_(std::move(completion)) {}
    SpinBarrier(const SpinBarrier&) = delete;
    SpinBarrier& operator=(const SpinBarrier&) = delete;

    void arrive_and_wait() {
        const std::uint32_t meeting = generation_.load(std::memory_order_acquire);
        if (arrived_.fetch_add(1, std::memory_order_acq_rel) + 1 == count_) {
            if (completion_) completion_();
            arrived_.store(0, std::memory_order_relaxed);  // before the release below
            generation_.store(meeting + 1, std::memory_order_release);
            generation_.notify_all();
            return;
        }
        for (int spin = 0; spin < kSpins; ++spin) {
            if (generation_.load(std::memory_order_acquire) != meeting) return;
            pause();
        }
        while (generation_.load(std::memory_order_acquire) == meeting)
            generation_.wait(meeting, std::memory_order_acquire);
    }

private:
    static constexpr int kSpins = 1000;
    static void pause() {
#if defined(__x86_64__) || defined(__i386__)
        _mm_pause();
#endif
    }

    const int count_;
    const std::function<void()> completion_;
    std::atomic<int> arrived_{0};
    std::atomic<std::uint32_t> generation_{0};
};

}  // namespace cloth
