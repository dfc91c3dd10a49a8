// Runs a 2 x 2 x 2 cube to load loss through ldem's C++ API and prints its peak.
#include <cstdio>

#include "ldem/Simulation.hpp"

int main() {
    ldem::CubeTestParams p = ldem::cubeTestDefaults();  // what ldem cube runs on its defaults
    ldem::setParameter(p, "size", 0.04);
    ldem::setParameter(p, "strain_rate", 0.5);
    ldem::setParameter(p, "stop_at", std::string("load_loss"));
    ldem::setParameter(p, "threads", std::int64_t(1));
    ldem::Simulation sim(ldem::cubeTestSpecimen(p), p.material, p.loading, p.run);
    const ldem::RunSummary s = sim.run();
    std::printf("peak %.6f MPa, %s\n", s.peakStress * 1e-6, s.stopReason.c_str());
    return s.stopReason == "load_lost" ? 0 : 1;
}
