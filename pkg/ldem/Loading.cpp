#include "ldem/Loading.hpp"

#include <cmath>

namespace ldem {

void LoadingParams::validate() const { LDEM_LOADING_PARAMETERS(LDEM_CHECK_MEMBER) }

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
