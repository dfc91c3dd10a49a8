// ldem-bench: time the whole time step of an N^3 cube (default material,
// uniform loading), or of the cylinder of diameter and height N modules cut
// from it (--shape cylinder: a clipped lattice), and print one line of JSON. `ldem bench` runs it; it is a
// separate program so that its peak resident memory is the run's own, with
// no interpreter around it. With --damaged it then pulls the same cube past
// its peak, to load loss (run() with stop_at = load_loss), and times the same
// steps from there: rows with softening bars leave the fast elastic path, so
// this is the speed of the part of a run that matters. Under mpirun each rank times its slab (Slab.hpp):
// the time per step is the whole lattice's, the memory and the bytes sent
// per step are those of the rank that uses the most.
//
//   ldem-bench --modules 48 --steps 200 --threads 2 [--repeats 5] [--shape box|cylinder] [--damaged 1]
//   mpirun -np 2 ldem-bench --modules 48 --steps 200 --threads 1
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>
#include <string>
#include <variant>
#include <vector>

#include <unistd.h>

#include "ldem/Comm.hpp"
#include "ldem/Parallel.hpp"
#include "ldem/Simulation.hpp"
#include "ldem/Slab.hpp"
#include "ldem/dynamics/SeparationStop.hpp"

namespace {
double seconds(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}
// Wall time of one whole step, averaged over `steps` steps [s].
double secondsPerStep(ldem::Simulation& sim, int steps) {
    const auto t = std::chrono::steady_clock::now();
    for (int s = 0; s < steps; ++s) sim.step();
    return seconds(t) / steps;
}
// Rows of bars on the law's slow path (some bar softening or broken), over all ranks.
std::int64_t softeningRows(const ldem::Simulation& sim, const ldem::Comm& comm) {
    std::int64_t rows = 0;
    std::visit([&](const auto& law) {
        for (std::uint8_t r : law.softeningRows()) rows += r != 0;
    }, sim.law());
    return comm.sum(rows);
}
// The damaged case: the cube pulled to load loss, then `steps` steps timed
// `repeats` times from there. Its JSON fields, each starting with a comma.
std::string damagedCase(ldem::Simulation& sim, int steps, int repeats, double elasticStep, const ldem::Comm& comm) {
    const auto t0 = std::chrono::steady_clock::now();
    ldem::CurvePoint last;
    const ldem::RunSummary s = sim.run([&](const ldem::CurvePoint& p) { return last = p, true; });
    sim.advance();  // run() stops at a record, after its forces: the rest of that step
    const double reach = seconds(t0);
    const double bars = double(sim.totalBars());
    const double rows = double(comm.sum(std::int64_t(sim.lattice().barRows.size())));
    const double softening = double(softeningRows(sim, comm));
    std::vector<double> perStep;
    for (int r = 0; r < repeats; ++r) perStep.push_back(secondsPerStep(sim, steps));
    const double step = comm.max(median(perStep));
    char json[512];
    std::snprintf(json, sizeof json,
                  ", \"damaged_stop_reason\": \"%s\", \"damaged_from_step\": %lld, \"damaged_stress_over_peak\": %.4f, "
                  "\"damaged_softening_row_share\": %.4f, \"damaged_bar_share\": %.5f, \"broken_bar_share\": %.5f, "
                  "\"damaged_softening_row_share_after\": %.4f, \"damaged_ns_per_bar_step\": %.4f, "
                  "\"damaged_over_elastic\": %.3f, \"damaged_reach_s\": %.3f",
                  s.stopReason.c_str(), (long long)last.step, last.stress / s.peakStress, softening / rows,
                  double(last.damaged) / bars, double(last.broken) / bars, double(softeningRows(sim, comm)) / rows,
                  step / bars * 1e9, step / elasticStep, reach);
    return json;
}
// Peak resident memory of this process [bytes]: VmHWM, which starts afresh at
// exec (getrusage's ru_maxrss would carry over the launching interpreter's).
long peakResidentBytes() {
    std::FILE* f = std::fopen("/proc/self/status", "r");
    char line[256];
    long kb = -1;
    while (f && std::fgets(line, sizeof line, f))
        if (std::sscanf(line, "VmHWM: %ld kB", &kb) == 1) break;
    if (f) std::fclose(f);
    return kb * 1024;
}

[[noreturn]] void usage(const char* msg) {
    std::fprintf(stderr, "ldem-bench: error: %s\nusage: ldem-bench --modules N --steps S --threads T [--repeats R] [--shape box|cylinder] [--damaged 0|1]\n", msg);
    std::exit(2);
}
// Modules of an N^3 box whose centres lie within the cylinder of axis z and diameter N.
std::vector<std::uint8_t> cylinderMask(int n) {
    std::vector<std::uint8_t> mask(std::size_t(n) * n * n);
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const double x = i + 0.5 - 0.5 * n, y = j + 0.5 - 0.5 * n;
                mask[i + std::size_t(n) * (j + std::size_t(n) * k)] = x * x + y * y <= 0.25 * n * n;
            }
    return mask;
}
}  // namespace

static int bench(int argc, char** argv, int& modules);

int main(int argc, char** argv) {
    // Idle OpenMP threads sleep rather than spin, as under `ldem` (py/ldem/__init__.py
    // says why); the runtime reads OMP_WAIT_POLICY as the program loads, before
    // main: the program starts again with it set. A user's own setting stands.
    if (!std::getenv("OMP_WAIT_POLICY") && setenv("OMP_WAIT_POLICY", "passive", 1) == 0)
        execv("/proc/self/exe", argv);  // returns only if it failed: then as it is
    int modules = 0;
    try {
        return bench(argc, argv, modules);
    } catch (const std::bad_alloc&) {  // above this process's memory limit (ulimit -v), set-up or steps
        std::fprintf(stderr, "ldem-bench: error: out of memory for the %d^3 lattice on rank %d of %d: split it over "
                     "more MPI ranks (mpirun -np P)\n", modules, ldem::Comm::world().rank(), ldem::Comm::world().size());
        return 2;
    }
}

static int bench(int argc, char** argv, int& modules) {
    modules = 24;
    int steps = 200, threads = 0, repeats = 5;
    std::string shape = "box";
    bool damaged = false;
    for (int a = 1; a < argc; ++a) {
        const std::string key = argv[a];
        if (a + 1 >= argc) usage(("missing value after " + key).c_str());
        if (key == "--shape") {
            shape = argv[++a];
            if (shape != "box" && shape != "cylinder") usage("--shape is box or cylinder");
            continue;
        }
        const int value = std::atoi(argv[++a]);
        if (key == "--modules") modules = value;
        else if (key == "--steps") steps = value;
        else if (key == "--threads") threads = value;
        else if (key == "--repeats") repeats = value;
        else if (key == "--damaged") damaged = value != 0;
        else usage(("unknown option " + key).c_str());
    }
    if (modules < 1 || steps < 1 || threads < 0 || repeats < 1) usage("values must be positive");

    ldem::RunParams run;
    run.threads = threads;
    run.stopAt = ldem::stopNamed("load_loss");  // the damaged case's run (the elastic timing calls step() alone)
    run.lossStopStrainRatio = 0;  // at the load loss itself, as before that stop had a floor
    const ldem::Comm& comm = ldem::Comm::world();
    const auto t0 = std::chrono::steady_clock::now();
    std::unique_ptr<ldem::Simulation> built;
    try {
        const std::vector<std::uint8_t> mask = shape == "box" ? std::vector<std::uint8_t>{} : cylinderMask(modules);
        built = std::make_unique<ldem::Simulation>(
            ldem::cubeTestSpecimen(modules, modules, modules, 0.02, ldem::Material{}, ldem::LoadingParams{}, mask,
                                   ldem::slabLayers(modules, comm.rank(), comm.size())),
            ldem::Material{}, ldem::LoadingParams{}, run);
    } catch (const std::invalid_argument& e) {  // e.g. more memory than the machine has: one line
        if (comm.root()) std::fprintf(stderr, "ldem-bench: error: %s\n", e.what());
        ldem::mpiFinalize();
        return 2;
    }
    ldem::Simulation& sim = *built;
    const double setup = seconds(t0);

    // Each repetition: `steps` whole steps (bar pass, node pass, integration,
    // boundary conditions, work and damping bookkeeping), plus the two halves
    // timed apart on a few extra steps.
    std::vector<double> perStep, forces, advance, separation;
    double bytesPerStep = 0;
    for (int r = 0; r < repeats; ++r) {
        const std::int64_t sent = comm.bytesSent();
        perStep.push_back(secondsPerStep(sim, steps));
        bytesPerStep = double(comm.bytesSent() - sent) / steps;
        double tf = 0, ta = 0;
        for (int s = 0; s < 10; ++s) {
            auto t = std::chrono::steady_clock::now();
            sim.computeForces();
            tf += seconds(t);
            t = std::chrono::steady_clock::now();
            sim.advance();
            ta += seconds(t);
        }
        forces.push_back(tf / 10), advance.push_back(ta / 10);
        // One separation test (union-find over the intact bars), the cost that
        // run() adds once per SeparationStop::checkSteps steps after the peak.
        const auto t = std::chrono::steady_clock::now();
        volatile bool joined = sim.facesJoined();
        (void)joined;
        separation.push_back(seconds(t));
    }
    // The whole lattice's bars; the slowest rank's times (every rank waits for it at each step).
    const double bars = double(sim.totalBars());
    const std::int64_t nodes = sim.totalNodes();
    const double step = comm.max(median(perStep)), force = comm.max(median(forces)), adv = comm.max(median(advance));
    const double sep = comm.max(median(separation));
    const double rss = comm.max(double(peakResidentBytes())), sent = comm.max(bytesPerStep);
    const std::string damagedFields = damaged ? damagedCase(sim, steps, repeats, step, comm) : "";
    if (comm.root())
        std::printf(
            "{\"shape\": \"%s\", \"modules\": %d, \"bars\": %lld, \"nodes\": %lld, \"steps\": %d, \"repeats\": %d, "
            "\"ranks\": %d, \"threads\": %d, \"ns_per_bar_step\": %.4f, \"ns_per_bar_forces\": %.4f, "
            "\"ns_per_bar_integration\": %.4f, \"separation_check_share\": %.4f, \"setup_s\": %.3f, "
            "\"peak_rss_bytes\": %.0f, \"bytes_per_bar\": %.2f, \"bytes_sent_per_rank_step\": %.0f%s}\n",
            shape.c_str(), modules, (long long)bars, (long long)nodes, steps, repeats, comm.size(), sim.threads(),
            step / bars * 1e9, force / bars * 1e9, adv / bars * 1e9,
            sep / (ldem::SeparationStop::checkSteps * step), setup, rss, rss * comm.size() / bars, sent,
            damagedFields.c_str());
    ldem::mpiFinalize();
    return 0;
}
