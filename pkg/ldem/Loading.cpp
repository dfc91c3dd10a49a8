#include "ldem/Loading.hpp"

#include <cmath>
#include <stdexcept>

namespace ldem {

LoadShape parseLoadShape(const std::string& name) {
    if (name == "uniform") return LoadShape::Uniform;
    if (name == "triangular") return LoadShape::Triangular;
    throw std::invalid_argument("unknown load '" + name + "' (expected uniform or triangular)");
}

std::string loadShapeName(LoadShape s) { return s == LoadShape::Uniform ? "uniform" : "triangular"; }

void LoadingParams::validate() const {
    if (!(strainRate > 0) || !std::isfinite(strainRate))
        throw std::invalid_argument("strain rate must be positive (got " + std::to_string(strainRate) + " 1/s)");
    if (!(rampTime >= 0) || !std::isfinite(rampTime))
        throw std::invalid_argument("ramp time must be >= 0 (got " + std::to_string(rampTime) + " s)");
    if (!(lossSpeedup >= 1) || !std::isfinite(lossSpeedup))
        throw std::invalid_argument("speed-up after load loss must be >= 1 (got " + std::to_string(lossSpeedup) + ")");
}

namespace {
// Integral over [0, t] of a velocity that rises from 0 to 1 as (1 - cos(pi t/t_r))/2.
double smoothRampIntegral(double t, double tr) {
    constexpr double pi = 3.14159265358979323846;
    if (t <= 0) return 0;
    if (t < tr) return 0.5 * (t - tr / pi * std::sin(pi * t / tr));
    return t - 0.5 * tr;
}
}  // namespace

double Drive::displacement(double t) const {
    const double U = v0 * smoothRampIntegral(t, rampTime);
    return t <= speedupStart ? U : U + (speedup - 1) * v0 * smoothRampIntegral(t - speedupStart, rampTime);
}

Constraints cubeTestConstraints(const Lattice& lat, const LoadingParams& p) {
    p.validate();
    Constraints c;
    c.mask.assign(lat.numNodes(), 0);
    c.height = lat.nz * lat.L0;
    c.faceArea = lat.nx * lat.L0 * lat.ny * lat.L0;
    const double width = lat.nx * lat.L0;
    auto prescribe = [&](std::int32_t n, int d, double w) {
        c.mask[n] |= std::uint8_t(1u << d);
        c.node.push_back(n), c.dim.push_back(std::uint8_t(d)), c.weight.push_back(w);
    };
    double weightSum = 0;
    for (int j = 0; j <= lat.ny; ++j)
        for (int i = 0; i <= lat.nx; ++i) {
            const auto bottom = lat.cornerId(i, j, 0), top = lat.cornerId(i, j, lat.nz);
            c.bottomNodes.push_back(bottom), c.topNodes.push_back(top);
            // Lower face: vertical DOF fixed; lateral fixed, or on rollers with only
            // the rigid-body motion pinned (x, y at one corner, y at the next).
            prescribe(bottom, 2, 0.0);
            const bool pin = (i == 0 && j == 0) || (i == lat.nx && j == 0);
            if (!p.bottomLateralFree || pin) {
                if (!p.bottomLateralFree || i == 0) prescribe(bottom, 0, 0.0);
                prescribe(bottom, 1, 0.0);
            }
            // Upper face: triangular varies linearly in x from 0 to 1.
            const double w = p.shape == LoadShape::Uniform ? 1.0 : lat.position(top)[0] / width;
            weightSum += w;
            if (!p.topLateralFree) prescribe(top, 0, 0.0), prescribe(top, 1, 0.0);
            prescribe(top, 2, w);
        }
    c.meanTopWeight = weightSum / c.topNodes.size();
    return c;
}

}  // namespace ldem
