#include "ldem/Lattice.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace ldem {

std::int64_t expectedNodeCount(int nx, int ny, int nz) {
    return std::int64_t(nx + 1) * (ny + 1) * (nz + 1) + std::int64_t(nx) * ny * nz;
}

std::int64_t expectedBarCount(int nx, int ny, int nz) {
    const std::int64_t edges = std::int64_t(nx) * (ny + 1) * (nz + 1) + std::int64_t(nx + 1) * ny * (nz + 1) +
                               std::int64_t(nx + 1) * (ny + 1) * nz;
    const std::int64_t centre = std::int64_t(nx - 1) * ny * nz + std::int64_t(nx) * (ny - 1) * nz +
                                std::int64_t(nx) * ny * (nz - 1);
    return edges + centre + 8 * std::int64_t(nx) * ny * nz;
}

namespace {

// Number of modules along one axis that touch a lattice line at index j of [0, n].
int modulesBeside(int j, int n) { return (j > 0 ? 1 : 0) + (j < n ? 1 : 0); }

class Builder {
public:
    Builder(Lattice& lat) : lat_(lat) {}

    // Starts a family; subsequent bars belong to it.
    void family(BarKind kind, std::array<double, 3> d0, double fullArea, double fullAf, double E) {
        const double L = std::sqrt(d0[0] * d0[0] + d0[1] * d0[1] + d0[2] * d0[2]);
        lat_.families.push_back({kind, d0, L, E * fullArea, fullAf});
    }
    void colourBegin() { begin_ = lat_.numBars(); }
    void colourEnd() {
        if (lat_.numBars() > begin_) lat_.colours.push_back({begin_, lat_.numBars()});
    }
    void bar(std::int32_t a, std::int32_t b, float share) {
        lat_.n1.push_back(a);
        lat_.n2.push_back(b);
        lat_.family.push_back(static_cast<std::uint8_t>(lat_.families.size() - 1));
        lat_.share.push_back(share);
    }

private:
    Lattice& lat_;
    std::int64_t begin_ = 0;
};

}  // namespace

Lattice buildCubicLattice(int nx, int ny, int nz, double L0, const Material& m) {
    if (nx < 1 || ny < 1 || nz < 1)
        throw std::invalid_argument("a lattice needs at least one module per direction");
    if (!(L0 > 0) || !std::isfinite(L0))
        throw std::invalid_argument("module size L0 must be positive (got " + std::to_string(L0) + " m)");
    m.validate();
    const std::int64_t nodes = expectedNodeCount(nx, ny, nz);
    if (nodes > std::int64_t(INT32_MAX)) throw std::invalid_argument("lattice too large for 32-bit node ids");

    Lattice lat;
    lat.nx = nx, lat.ny = ny, lat.nz = nz, lat.L0 = L0;
    lat.x0.resize(nodes), lat.y0.resize(nodes), lat.z0.resize(nodes);
    lat.mass.assign(nodes, 0.0);
    for (int k = 0; k <= nz; ++k)
        for (int j = 0; j <= ny; ++j)
            for (int i = 0; i <= nx; ++i) {
                const auto id = lat.cornerId(i, j, k);
                lat.x0[id] = i * L0, lat.y0[id] = j * L0, lat.z0[id] = k * L0;
            }
    const double moduleMass = m.rho * L0 * L0 * L0;
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                const auto c = lat.centreId(i, j, k);
                lat.x0[c] = (i + 0.5) * L0, lat.y0[c] = (j + 0.5) * L0, lat.z0[c] = (k + 0.5) * L0;
                lat.mass[c] += 0.5 * moduleMass;
                for (int dk = 0; dk < 2; ++dk)
                    for (int dj = 0; dj < 2; ++dj)
                        for (int di = 0; di < 2; ++di)
                            lat.mass[lat.cornerId(i + di, j + dj, k + dk)] += moduleMass / 16.0;
            }

    const double An = normalBarArea(m.nu, L0), Ad = diagonalBarArea(m.nu, L0);
    const double Afn = normalFractureArea(m.ca, L0), Afd = diagonalFractureArea(m.ca, L0);
    const int n[3] = {nx, ny, nz};
    lat.n1.reserve(expectedBarCount(nx, ny, nz));
    lat.n2.reserve(expectedBarCount(nx, ny, nz));
    Builder build(lat);

    // Edge bars along axis a, one colour per parity of the index along a.
    for (int a = 0; a < 3; ++a) {
        std::array<double, 3> d0{0, 0, 0};
        d0[a] = L0;
        build.family(BarKind::Edge, d0, An, Afn, m.E);
        for (int parity = 0; parity < 2; ++parity) {
            build.colourBegin();
            int e[3];
            for (e[2] = 0; e[2] <= nz; ++e[2])
                for (e[1] = 0; e[1] <= ny; ++e[1])
                    for (e[0] = 0; e[0] <= nx; ++e[0]) {
                        if (e[a] >= n[a] || (e[a] & 1) != parity) continue;
                        int s = 1;  // modules sharing this edge: product over the two other axes
                        for (int o = 0; o < 3; ++o)
                            if (o != a) s *= modulesBeside(e[o], n[o]);
                        int f[3] = {e[0], e[1], e[2]};
                        ++f[a];
                        build.bar(lat.cornerId(e[0], e[1], e[2]), lat.cornerId(f[0], f[1], f[2]), s / 4.0f);
                    }
            build.colourEnd();
        }
    }
    // Centre-centre bars along axis a, one colour per parity.
    for (int a = 0; a < 3; ++a) {
        std::array<double, 3> d0{0, 0, 0};
        d0[a] = L0;
        build.family(BarKind::CentreCentre, d0, An, Afn, m.E);
        for (int parity = 0; parity < 2; ++parity) {
            build.colourBegin();
            int c[3];
            for (c[2] = 0; c[2] < nz; ++c[2])
                for (c[1] = 0; c[1] < ny; ++c[1])
                    for (c[0] = 0; c[0] < nx; ++c[0]) {
                        if (c[a] + 1 >= n[a] || (c[a] & 1) != parity) continue;
                        int f[3] = {c[0], c[1], c[2]};
                        ++f[a];
                        build.bar(lat.centreId(c[0], c[1], c[2]), lat.centreId(f[0], f[1], f[2]), 1.0f);
                    }
            build.colourEnd();
        }
    }
    // Diagonals: centre (i,j,k) -> corner (i+di, j+dj, k+dk); each family is one colour.
    for (int dk = 0; dk < 2; ++dk)
        for (int dj = 0; dj < 2; ++dj)
            for (int di = 0; di < 2; ++di) {
                build.family(BarKind::Diagonal, {(di - 0.5) * L0, (dj - 0.5) * L0, (dk - 0.5) * L0}, Ad, Afd, m.E);
                build.colourBegin();
                for (int k = 0; k < nz; ++k)
                    for (int j = 0; j < ny; ++j)
                        for (int i = 0; i < nx; ++i)
                            build.bar(lat.centreId(i, j, k), lat.cornerId(i + di, j + dj, k + dk), 1.0f);
                build.colourEnd();
            }
    return lat;
}

}  // namespace ldem
