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
// region (an exception cannot leave one): there it does nothing.
#pragma once
#include <algorithm>
#include <chrono>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace ldem {

using InterruptPoll = void (*)();  // returns, or throws to stop the loop
inline constexpr std::chrono::milliseconds kInterruptPollPeriod{100};

inline InterruptPoll& interruptPoll() {
    static InterruptPoll poll = nullptr;
    return poll;
}

inline void setInterruptPoll(InterruptPoll poll) { interruptPoll() = poll; }

class InterruptCheck {
public:
    void operator()() {
        const InterruptPoll poll = interruptPoll();
        if (!poll || ++calls_ < stride_) return;
#ifdef _OPENMP
        if (omp_in_parallel()) return;
#endif
        calls_ = 0;
        const Clock::time_point now = Clock::now();
        if (now - lastRead_ < std::chrono::milliseconds(1)) stride_ = std::min(2 * stride_, 1024u);
        else if (stride_ > 1) stride_ /= 2;
        lastRead_ = now;
        thread_local Clock::time_point nextPoll{};  // shared by the loops: one poll per period
        if (now < nextPoll) return;
        nextPoll = now + kInterruptPollPeriod;
        poll();
    }

private:
    using Clock = std::chrono::steady_clock;
    unsigned calls_ = 0, stride_ = 1;
    Clock::time_point lastRead_{};
};

}  // namespace ldem
