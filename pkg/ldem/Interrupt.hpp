// A long loop's chance to hear a signal (Ctrl-C, SIGTERM). The core knows no
// signal: the program installs a poll (the Python bindings: Python's signal
// handlers, run under the GIL, their exception thrown on as a C++ one), and
// a loop of the set-up or of the run calls an InterruptCheck of its own once
// per pass of an outer loop (a time step, a Lanczos iteration, a layer of the
// lattice build). The check reads the clock about once a millisecond (every
// `stride` calls, the stride doubled or halved to keep that pace: a call of a
// fast pass costs a count, 1 ns, not a clock read, 40 ns against the 10 us
// step of the smallest cube; each loop has its own, so a slow loop after a
// fast one does not inherit its stride) and polls every kInterruptPollPeriod:
// a signal is heard within that time plus a pass or two. Never in an OpenMP
// region (an exception cannot leave one): there it does nothing; a parallel
// loop of the set-up runs as interruptibleFor, in chunks with checks between.
#pragma once
#include <algorithm>
#include <chrono>
#include <cstdint>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace ldem {

using InterruptPoll = void (*)();  // returns, or throws to stop the loop
inline constexpr std::chrono::milliseconds kInterruptPollPeriod{100};
// The wall time of a chunk of interruptibleFor: ten OpenMP regions per poll
// period, each one's start tens of microseconds under the passive wait.
inline constexpr std::chrono::milliseconds kInterruptChunk{10};

inline InterruptPoll& interruptPoll() {
    static InterruptPoll poll = nullptr;
    return poll;
}

inline void setInterruptPoll(InterruptPoll poll) { interruptPoll() = poll; }

inline bool inParallelRegion() {
#ifdef _OPENMP
    return omp_in_parallel();
#else
    return false;
#endif
}

// Polls if kInterruptPollPeriod has passed since this thread's last poll
// (shared by the loops: one poll per period); now: the clock, just read.
inline void pollIfDue(std::chrono::steady_clock::time_point now) {
    thread_local std::chrono::steady_clock::time_point nextPoll{};
    if (now < nextPoll) return;
    nextPoll = now + kInterruptPollPeriod;
    if (const InterruptPoll poll = interruptPoll()) poll();
}

class InterruptCheck {
public:
    void operator()() {
        if (!interruptPoll() || ++calls_ < stride_ || inParallelRegion()) return;
        calls_ = 0;
        const Clock::time_point now = Clock::now();
        if (now - lastRead_ < std::chrono::milliseconds(1)) stride_ = std::min(2 * stride_, 1024u);
        else if (stride_ > 1) stride_ /= 2;
        lastRead_ = now;
        pollIfDue(now);
    }

private:
    using Clock = std::chrono::steady_clock;
    unsigned calls_ = 0, stride_ = 1;
    Clock::time_point lastRead_{};
};

// for (i = begin; i < end; ++i) body(i) across the OpenMP threads (static
// schedule), with a poll installed in chunks of about kInterruptChunk of
// work, the poll due checked after each (the clock is read there anyway: no
// stride): one region of seconds (the correlated G_f field's 512 cosines a
// bar) heard no signal. The chunk grows or halves to keep the master
// thread's share of it at that time, whatever a pass costs; its share, not
// the region's, which holds the other threads' start and join: on a loaded
// machine under the active wait these alone took 5 to 20 ms, and chunks
// timed with them stayed at one pass (an 8^3 field took 15 s, not 0.2).
// Only for a body whose passes are independent (each writes its own
// elements): then where the range is cut changes no result, to the bit.
template <class Body>
void interruptibleFor(std::int64_t begin, std::int64_t end, Body body) {
    if (!interruptPoll() || inParallelRegion()) {  // nothing to hear, or no poll allowed: one region
#pragma omp parallel for schedule(static)
        for (std::int64_t i = begin; i < end; ++i) body(i);
        return;
    }
    using Clock = std::chrono::steady_clock;
    std::int64_t chunk = 1;
    for (std::int64_t c0 = begin; c0 < end;) {
        const std::int64_t c1 = c0 + std::min(chunk, end - c0);
        Clock::duration work{};
#pragma omp parallel
        {
            const Clock::time_point t0 = Clock::now();
#pragma omp for schedule(static) nowait
            for (std::int64_t i = c0; i < c1; ++i) body(i);
#ifdef _OPENMP
            if (omp_get_thread_num() == 0)
#endif
                work = Clock::now() - t0;
        }
        if (work < kInterruptChunk / 16) chunk *= 8;  // fewer regions to its size: each costs its start
        else if (work < kInterruptChunk / 2) chunk *= 2;
        else if (work > 2 * kInterruptChunk && chunk > 1) chunk /= 2;
        c0 = c1;
        pollIfDue(Clock::now());
    }
}

}  // namespace ldem
