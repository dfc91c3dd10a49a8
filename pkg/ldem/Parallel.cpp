#include "ldem/Parallel.hpp"

#include <sched.h>

#include <cctype>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace ldem {

namespace {
// Idle and total jiffies of each allowed core ("cpuN" lines of /proc/stat);
// empty if it cannot be read.
std::vector<std::pair<double, double>> coreTimes(const cpu_set_t& allowed) {
    std::vector<std::pair<double, double>> out;
    std::ifstream in("/proc/stat");
    std::string line;
    while (std::getline(in, line)) {
        if (line.compare(0, 3, "cpu") != 0 || line.size() < 4 || !std::isdigit(static_cast<unsigned char>(line[3])))
            continue;
        std::istringstream fields(line.substr(3));
        int cpu = 0;
        fields >> cpu;
        if (cpu < 0 || cpu >= CPU_SETSIZE || !CPU_ISSET(cpu, &allowed)) continue;
        double v = 0, total = 0, idle = 0;
        for (int k = 0; k < 8 && fields >> v; ++k) {  // user .. steal (guest is within user)
            total += v;
            if (k == 3 || k == 4) idle += v;  // idle, iowait
        }
        out.emplace_back(idle, total);
    }
    return out;
}

cpu_set_t affinity() {
    cpu_set_t set;
    CPU_ZERO(&set);
    if (sched_getaffinity(0, sizeof set, &set) != 0)
        for (unsigned c = 0; c < std::max(1u, std::thread::hardware_concurrency()); ++c) CPU_SET(c, &set);
    return set;
}
}  // namespace

int allowedCores() {
    const cpu_set_t set = affinity();
    int cores = std::max(1, CPU_COUNT(&set));
    std::ifstream quota("/sys/fs/cgroup/cpu.max");  // "max 100000" or "200000 100000": quota and period [us]
    std::string q;
    double period = 0;
    if (quota >> q >> period && q != "max" && period > 0)
        cores = std::max(1, std::min(cores, int(std::ceil(std::atof(q.c_str()) / period))));
    return cores;
}

double idleCores(double seconds) {
    const cpu_set_t set = affinity();
    const auto before = coreTimes(set);
    std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
    const auto after = coreTimes(set);
    if (before.empty() || before.size() != after.size()) return allowedCores();  // unknown: as if idle
    double idle = 0;
    for (std::size_t c = 0; c < before.size(); ++c) {
        const double total = after[c].second - before[c].second;
        idle += total > 0 ? (after[c].first - before[c].first) / total : 1.0;
    }
    return std::min(idle, double(allowedCores()));
}

int environmentThreads() {
    const char* env = std::getenv("OMP_NUM_THREADS");
    char* end = nullptr;
    const long n = env ? std::strtol(env, &end, 10) : 0;
    return env && end != env && (*end == '\0' || *end == ',') && n > 0 ? int(std::min<long>(n, 1 << 20)) : 0;
}

int threadsFor(int requested, std::int64_t bars, int processes) {
#ifdef _OPENMP
    const int cores = allowedCores();
    if (requested > 0) return std::min(requested, cores);
    if (const int env = environmentThreads()) return std::min(env, cores);
    if (defaultThreadCount(bars, cores, processes) == 1) return 1;
    return defaultThreadCount(bars, idleCores(), processes);
#else
    (void)requested, (void)bars, (void)processes;
    return 1;
#endif
}

}  // namespace ldem
