#include "ldem/Comm.hpp"

#include <cstdlib>
#include <stdexcept>

#ifdef LDEM_MPI
#include <mpi.h>
#endif

namespace ldem {

// MPI starts at the first use of the world (under mpirun), so that a process
// that never splits a lattice (ldem bench's launcher) leaves MPI to its child.
Comm& Comm::instance() {
    static Comm w;
    return w;
}

const Comm& Comm::world() {
    static const bool started = (mpiInit(), true);
    (void)started;
    return instance();
}


const Comm& Comm::self() {
    static const Comm alone;
    return alone;
}

bool mpiLaunched() { return std::getenv("OMPI_COMM_WORLD_SIZE") || std::getenv("PMI_RANK") || std::getenv("PMIX_RANK"); }

#ifdef LDEM_MPI
bool mpiAvailable() { return true; }

void mpiInit() {
    int initialised = 0;
    MPI_Initialized(&initialised);
    if (initialised || !mpiLaunched()) return;
    int provided = 0;
    // OpenMP threads inside a rank never call MPI: FUNNELED is enough.
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    Comm& w = Comm::instance();
    MPI_Comm_rank(MPI_COMM_WORLD, &w.rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &w.size_);
}

void mpiFinalize() {
    int initialised = 0, finalised = 0;
    MPI_Initialized(&initialised);
    MPI_Finalized(&finalised);
    if (initialised && !finalised) MPI_Finalize();
}

void Comm::exchangeWithNeighbours(const std::vector<double>& toBelow, const std::vector<double>& toAbove,
                                  std::vector<double>& fromBelow, std::vector<double>& fromAbove) const {
    if (size_ == 1) return;
    const int below = rank_ > 0 ? rank_ - 1 : MPI_PROC_NULL, above = rank_ + 1 < size_ ? rank_ + 1 : MPI_PROC_NULL;
    MPI_Request req[4];
    // Tags: 0 travels down, 1 travels up.
    MPI_Irecv(fromAbove.data(), int(fromAbove.size()), MPI_DOUBLE, above, 0, MPI_COMM_WORLD, &req[0]);
    MPI_Irecv(fromBelow.data(), int(fromBelow.size()), MPI_DOUBLE, below, 1, MPI_COMM_WORLD, &req[1]);
    MPI_Isend(toBelow.data(), int(toBelow.size()), MPI_DOUBLE, below, 0, MPI_COMM_WORLD, &req[2]);
    MPI_Isend(toAbove.data(), int(toAbove.size()), MPI_DOUBLE, above, 1, MPI_COMM_WORLD, &req[3]);
    MPI_Waitall(4, req, MPI_STATUSES_IGNORE);
    bytesSent_ += std::int64_t(((below != MPI_PROC_NULL ? toBelow.size() : 0) +
                                (above != MPI_PROC_NULL ? toAbove.size() : 0)) * sizeof(double));
}

std::vector<double> Comm::allGather(const std::vector<double>& mine) const {
    if (size_ == 1) return mine;
    int n = int(mine.size());
    std::vector<int> counts(size_), displs(size_, 0);
    MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
    for (int r = 1; r < size_; ++r) displs[r] = displs[r - 1] + counts[r - 1];
    std::vector<double> all(std::size_t(displs.back() + counts.back()));
    MPI_Allgatherv(mine.data(), n, MPI_DOUBLE, all.data(), counts.data(), displs.data(), MPI_DOUBLE, MPI_COMM_WORLD);
    return all;
}

std::vector<std::int64_t> Comm::gather(const std::vector<std::int64_t>& mine) const {
    if (size_ == 1) return mine;
    int n = int(mine.size());
    std::vector<int> counts(size_), displs(size_, 0);
    MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
    for (int r = 1; r < size_; ++r) displs[r] = displs[r - 1] + counts[r - 1];
    std::vector<std::int64_t> all(root() ? std::size_t(displs.back() + counts.back()) : 0);
    MPI_Gatherv(mine.data(), n, MPI_INT64_T, all.data(), counts.data(), displs.data(), MPI_INT64_T, 0,
                MPI_COMM_WORLD);
    return all;
}

bool Comm::broadcast(bool value) const {
    if (size_ == 1) return value;
    int v = value;
    MPI_Bcast(&v, 1, MPI_INT, 0, MPI_COMM_WORLD);
    return v != 0;
}

std::int64_t Comm::sum(std::int64_t value) const {
    if (size_ == 1) return value;
    std::int64_t out = 0;
    MPI_Allreduce(&value, &out, 1, MPI_INT64_T, MPI_SUM, MPI_COMM_WORLD);
    return out;
}

double Comm::max(double value) const {
    if (size_ == 1) return value;
    double out = 0;
    MPI_Allreduce(&value, &out, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    return out;
}
#else
bool mpiAvailable() { return false; }
void mpiInit() {
    if (mpiLaunched() && std::getenv("OMPI_COMM_WORLD_SIZE") && std::atoi(std::getenv("OMPI_COMM_WORLD_SIZE")) > 1)
        throw std::runtime_error("ldem was built without MPI (install libopenmpi-dev and rebuild)");
}
void mpiFinalize() {}
void Comm::exchangeWithNeighbours(const std::vector<double>&, const std::vector<double>&, std::vector<double>&,
                                  std::vector<double>&) const {}
std::vector<double> Comm::allGather(const std::vector<double>& mine) const { return mine; }
std::vector<std::int64_t> Comm::gather(const std::vector<std::int64_t>& mine) const { return mine; }
bool Comm::broadcast(bool value) const { return value; }
std::int64_t Comm::sum(std::int64_t value) const { return value; }
double Comm::max(double value) const { return value; }
#endif

}  // namespace ldem
