// The processes one lattice is split over (MPI ranks, one slab of module
// layers each; Slab.hpp), or one process alone. Everything the time-step loop
// exchanges goes through this small interface, so the core builds and runs
// the same without MPI (a single rank), and under `mpirun -np P`.
#pragma once
#include <cstdint>
#include <vector>

namespace ldem {

class Comm {
public:
    // MPI_COMM_WORLD once mpiInit() has run under mpirun; else one rank alone.
    static const Comm& world();
    static const Comm& self();  // this process alone
    int rank() const { return rank_; }
    int size() const { return size_; }
    bool root() const { return rank_ == 0; }

    // Sends toBelow to rank - 1 and toAbove to rank + 1, and receives
    // fromAbove.size() values from rank + 1 and fromBelow.size() from rank - 1
    // (where those ranks exist), all four at once.
    void exchangeWithNeighbours(const std::vector<double>& toBelow, const std::vector<double>& toAbove,
                                std::vector<double>& fromBelow, std::vector<double>& fromAbove) const;
    // Every rank's `mine`, concatenated in rank order, on every rank.
    std::vector<double> allGather(const std::vector<double>& mine) const;
    // Every rank's `mine`, concatenated in rank order, on rank 0 (empty elsewhere).
    std::vector<std::int64_t> gather(const std::vector<std::int64_t>& mine) const;
    // Rank 0's value on every rank.
    bool broadcast(bool value) const;
    std::int64_t sum(std::int64_t value) const;  // over ranks (integers: exact in any order)
    double max(double value) const;
    // Bytes this rank has sent to its neighbours since the start (ldem-bench prints them).
    std::int64_t bytesSent() const { return bytesSent_; }

private:
    Comm() = default;
    static Comm& instance();
    int rank_ = 0, size_ = 1;
    mutable std::int64_t bytesSent_ = 0;
    friend void mpiInit();
};

// Whether this process was started by mpirun (OpenMPI's environment says so).
bool mpiLaunched();
// Initialises MPI if launched by mpirun and ldem was built with MPI; else throws
// std::runtime_error if launched by mpirun without MPI support. Idempotent.
void mpiInit();
void mpiFinalize();
// Whether this build can run under MPI.
bool mpiAvailable();

}  // namespace ldem
