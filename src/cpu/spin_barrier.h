// The barrier between the passes of one threaded step (cpu_solver.h Team, cpu_multigrid.h
// CycleThreads). Its threads meet thousands of times a second, usually a few microseconds
// apart: an arrival spins first, for 50 µs by the clock (a pause lasts 10 ns on one Xeon and
// 50 on another, so a count of pauses is no measure), then sleeps on the generation (a futex),
// so that a thread whose partner was descheduled does not hold its core. std::barrier sleeps almost
// at once: 9–14 µs a meeting of two threads on this project's machines, against 0.2–0.3 µs spinning
// (docs/performance.md, "The passes' barrier").
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <utility>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace cloth {

class SpinBarrier {
public:
    // `completion` runs once a meeting, on the last thread to arrive, before any thread leaves.
    // count ≥ 1 threads. The completion must not throw: arrive_and_wait is noexcept, so a throw
    // ends the process instead of leaving the others waiting forever.
    explicit SpinBarrier(int count, std::function<void()> completion = {})
        : count_(count), completion_(std::move(completion)) {
        if (count < 1) throw std::invalid_argument("SpinBarrier: count must be at least 1");
    }
    SpinBarrier(const SpinBarrier&) = delete;
    SpinBarrier& operator=(const SpinBarrier&) = delete;

    void arrive_and_wait() noexcept {
        const std::uint32_t meeting = generation_.load(std::memory_order_acquire);
        if (arrived_.fetch_add(1, std::memory_order_acq_rel) + 1 == count_) {
            if (completion_) completion_();
            arrived_.store(0, std::memory_order_relaxed);  // before the publication below
            // seq_cst: a full fence between the publication and notify_all's look at the
            // waiters, which a release store would let the CPU reorder (a lost wake-up).
            generation_.store(meeting + 1, std::memory_order_seq_cst);
            generation_.notify_all();
            return;
        }
        const auto until = std::chrono::steady_clock::now() + kSpin;
        for (int spin = 1;; ++spin) {
            if (generation_.load(std::memory_order_acquire) != meeting) return;
            pause();
            if (spin % 16 == 0 && std::chrono::steady_clock::now() >= until) break;
        }
        while (generation_.load(std::memory_order_acquire) == meeting)
            generation_.wait(meeting, std::memory_order_acquire);
    }

private:
    static constexpr std::chrono::microseconds kSpin{50};  // docs/performance.md, the barrier
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
