#include "ldem/Specimen.hpp"


namespace ldem {

void Prescribed::add(std::int32_t n, int d, double w) {
    mask[n] |= std::uint8_t(1u << d);
    node.push_back(n), dim.push_back(std::uint8_t(d)), weight.push_back(w);
}

Specimen cubeTestSpecimen(int nx, int ny, int nz, double L0, const Material& m, const LoadingParams& p) {
    m.validate();
    p.validate();
    Specimen s;
    s.lattice = buildCubicLattice(nx, ny, nz, L0, m);
    const Lattice& lat = s.lattice;
    Prescribed& c = s.prescribed;
    c.mask.assign(lat.numNodes(), 0);
    std::vector<std::int32_t>& bottomNodes = s.groups["bottom"];
    std::vector<std::int32_t>& topNodes = s.groups["top"];
    const double width = lat.nx * lat.L0;
    double weightSum = 0;
    for (int j = 0; j <= lat.ny; ++j)
        for (int i = 0; i <= lat.nx; ++i) {
            const auto bottom = lat.cornerId(i, j, 0), top = lat.cornerId(i, j, lat.nz);
            bottomNodes.push_back(bottom), topNodes.push_back(top);
            // Lower face: vertical DOF fixed; lateral fixed, or on rollers with only
            // the rigid-body motion pinned (x, y at one corner, y at the next).
            c.add(bottom, 2, 0.0);
            const bool pin = (i == 0 && j == 0) || (i == lat.nx && j == 0);
            if (!p.bottomLateralFree || pin) {
                if (!p.bottomLateralFree || i == 0) c.add(bottom, 0, 0.0);
                c.add(bottom, 1, 0.0);
            }
            // Upper face: triangular varies linearly in x from 0 to 1.
            const double w = p.shape == LoadShape::Uniform ? 1.0 : lat.position(top)[0] / width;
            weightSum += w;
            if (!p.topLateralFree) c.add(top, 0, 0.0), c.add(top, 1, 0.0);
            c.add(top, 2, w);
        }
    Measures& ms = s.measures;
    ms.support = "bottom", ms.loaded = "top", ms.dim = 2;
    ms.area = lat.nx * lat.L0 * lat.ny * lat.L0;
    ms.gaugeLength = lat.nz * lat.L0;
    ms.meanDriveWeight = weightSum / topNodes.size();
    return s;
}

}  // namespace ldem
