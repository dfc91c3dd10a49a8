#include "ldem/Lattice.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include "ldem/Interrupt.hpp"

#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>

#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>
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

// The share of bar (p, q, r) of family fam in lat (whose mask is set): the
// fraction of a full bar's EA and Af it carries, 0 if the bar does not exist.
double barShare(const Lattice& lat, const BarFamily& fam, int p, int q, int r) {
    switch (fam.kind) {
        case BarKind::Edge: {
            // k/4, k = present modules around the edge; they have the edge's
            // index along it and its index or one less across it.
            const int u = (fam.axis + 1) % 3, v = (fam.axis + 2) % 3;
            int k = 0;
            for (int c = 0; c < 4; ++c) {
                std::array<int, 3> idx{p, q, r};
                idx[u] -= c & 1, idx[v] -= c >> 1;
                k += lat.present(idx[0], idx[1], idx[2]);
            }
            return k / 4.0;
        }
        case BarKind::CentreCentre:
            return lat.present(p, q, r) && lat.present(p + fam.offsetB[0], q + fam.offsetB[1], r + fam.offsetB[2])
                       ? 1.0
                       : 0.0;
        case BarKind::Diagonal:
            return lat.present(p, q, r) ? 1.0 : 0.0;
    }
    return 0.0;
}

// Splits a row of bars with shares s (0 = no bar) into runs [p0, p1) of
// existing bars that one BarRow can carry: the hot loop gives a row's first
// and last bar endShare and the others share, so a run's shares must read
// e, i, i, ..., i, e. Each run is taken as long as possible from its start,
// so a row that already fits (every row of a full box) stays one run.
std::vector<std::pair<int, int>> rowSegments(const std::vector<double>& s) {
    std::vector<std::pair<int, int>> out;
    const int n = int(s.size());
    for (int p0 = 0; p0 < n;) {
        if (s[p0] == 0) {
            ++p0;
            continue;
        }
        int p1 = p0 + 1;
        if (p1 < n && s[p1] != 0) {
            int last = p1;  // the last bar with the interior share s[p0 + 1]
            while (last + 1 < n && s[last + 1] == s[p1]) ++last;
            if (s[p1] == s[p0]) p1 = last + 1;                          // e, e, ..., e
            else if (last + 1 < n && s[last + 1] == s[p0]) p1 = last + 2;  // e, i, ..., i, e
        }
        out.emplace_back(p0, p1);
        p0 = p1;
    }
    return out;
}

}  // namespace

std::array<double, 3> Lattice::position(std::int32_t node) const {
    const std::int32_t nc = numCorners();
    if (node < nc) {
        const int i = node % (nx + 1), j = (node / (nx + 1)) % (ny + 1), k = node / ((nx + 1) * (ny + 1));
        return {i * L0, j * L0, (k + kOffset) * L0};
    }
    const std::int32_t c = node - nc;
    const int i = c % nx, j = (c / nx) % ny, k = c / (nx * ny);
    return {(i + 0.5) * L0, (j + 0.5) * L0, (k + kOffset + 0.5) * L0};
}

std::int64_t Lattice::globalNode(std::int32_t n) const {
    const std::int64_t plane = std::int64_t(nx + 1) * (ny + 1), cells = std::int64_t(nx) * ny;
    if (n < numCorners()) return n + plane * kOffset;
    return plane * (nzTotal + 1) + (n - numCorners()) + cells * kOffset;
}

std::int32_t Lattice::localNode(std::int64_t g) const {
    const std::int64_t plane = std::int64_t(nx + 1) * (ny + 1), cells = std::int64_t(nx) * ny;
    const std::int64_t corners = plane * (nzTotal + 1);
    const std::int64_t local = g < corners ? g - plane * kOffset : g - corners - cells * kOffset;
    const std::int64_t count = g < corners ? plane * (nz + 1) : cells * nz;
    if (g < 0 || local < 0 || local >= count) return -1;
    return std::int32_t(g < corners ? local : numCorners() + local);
}

std::pair<std::int64_t, std::int64_t> Lattice::ownedBars() const {
    auto firstOfLayer = [this](int m) {
        const std::int32_t r = barLayerStart[m];
        return r < std::int32_t(barRows.size()) ? barRows[r].first : numBars();
    };
    return {firstOfLayer(ownBegin), firstOfLayer(ownEnd)};
}

const BarRow& Lattice::rowOf(std::int64_t bar) const {
    auto it = std::upper_bound(barRows.begin(), barRows.end(), bar,
                               [](std::int64_t b, const BarRow& row) { return b < row.first; });
    return *(it - 1);
}

BarTable listBars(const Lattice& lat) {
    BarTable t;
    const std::size_t n = std::size_t(lat.numBars());
    t.n1.resize(n), t.n2.resize(n), t.family.resize(n), t.share.resize(n), t.EA.resize(n), t.Af.resize(n),
        t.L.resize(n);
    forEachBar(lat, [&](std::int64_t b, std::int32_t a, std::int32_t c, const BarRow& row, int p) {
        const BarFamily& fam = lat.families[row.family];
        t.n1[b] = a, t.n2[b] = c, t.family[b] = row.family, t.share[b] = row.shareAt(p);
        t.EA[b] = fam.EA * t.share[b], t.Af[b] = fam.Af * t.share[b], t.L[b] = fam.L;
    });
    return t;
}

std::array<std::vector<double>, 3> nodePositions(const Lattice& lat) {
    std::array<std::vector<double>, 3> x;
    for (auto& c : x) c.resize(lat.numNodes());
    for (std::int32_t n = 0; n < lat.numNodes(); ++n) {
        const auto p = lat.position(n);
        x[0][n] = p[0], x[1][n] = p[1], x[2][n] = p[2];
    }
    return x;
}

std::int64_t memoryEstimate(int nx, int ny, int nz) { return kBytesPerBar * expectedBarCount(nx, ny, nz); }

namespace {

// The first number of `path` (0 if the file cannot be read or holds none: "max").
double readNumber(const std::string& path) {
    std::ifstream f(path);
    double x = 0;
    return f >> x ? x : 0;
}

// The cgroup's limit less its usage: v2's memory.max - memory.current, else v1's memory.limit_in_bytes -
// memory.usage_in_bytes; -1 if there is no limit (a v1 "no limit" is about 2^63).
double cgroupHeadroom() {
    std::ifstream f("/proc/self/cgroup");
    for (std::string line; std::getline(f, line);) {
        const auto colon = line.find(':'), second = line.find(':', colon + 1);
        if (colon == std::string::npos || second == std::string::npos) continue;
        const std::string controllers = line.substr(colon + 1, second - colon - 1), path = line.substr(second + 1);
        std::vector<std::pair<std::string, std::string>> files;  // (limit, usage), the process's cgroup first
        if (line.compare(0, 3, "0::") == 0)
            files = {{"/sys/fs/cgroup" + path + "/memory.max", "/sys/fs/cgroup" + path + "/memory.current"}};
        else if (controllers == "memory")
            for (const std::string& dir : {"/sys/fs/cgroup/memory" + path, std::string("/sys/fs/cgroup/memory")})
                files.push_back({dir + "/memory.limit_in_bytes", dir + "/memory.usage_in_bytes"});
        for (const auto& [limitFile, usageFile] : files)
            if (const double limit = readNumber(limitFile); limit > 0 && limit < 1e18)
                return std::max(0.0, limit - readNumber(usageFile));
    }
    return -1;
}

}  // namespace

MemoryLimit memoryLimit() {
    // The smallest room the lattice may take: the machine's available memory (MemAvailable), the cgroup's
    // limit less its usage, the address-space limit (ulimit -v) less the process's present size. (The
    // estimate's margin refuses some lattices that would run under a tight ulimit: the refusal says which.)
    const long pageSize = sysconf(_SC_PAGE_SIZE);
    MemoryLimit have{0, "this machine has"};
    {
        std::ifstream meminfo("/proc/meminfo");
        for (std::string key; meminfo >> key;) {
            double kB = 0;
            if (key == "MemAvailable:" && meminfo >> kB) {
                have = {kB * 1024, "this machine has available"};
                break;
            }
            meminfo.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
        }
        if (have.bytes == 0 && sysconf(_SC_AVPHYS_PAGES) > 0 && pageSize > 0)
            have = {double(sysconf(_SC_AVPHYS_PAGES)) * pageSize, "this machine has available"};
    }
    if (const double cgroup = cgroupHeadroom(); cgroup >= 0 && (have.bytes == 0 || cgroup < have.bytes))
        have = {cgroup, "the cgroup's memory limit (memory.max) leaves"};
    rlimit as{};
    if (getrlimit(RLIMIT_AS, &as) == 0 && as.rlim_cur != RLIM_INFINITY) {
        const double size = readNumber("/proc/self/statm") * double(pageSize);  // the address space in use
        const double room = std::max(0.0, double(as.rlim_cur) - size);
        if (have.bytes == 0 || room < have.bytes) have = {room, "the address-space limit (ulimit -v) leaves"};
    }
    return have;
}

std::string latticeMisfit(int nx, int ny, int nz, int k0, int k1, const MemoryLimit& have) {
    const int kLo = std::max(k0 - 1, 0), kHi = std::min(k1 + 1, nz);  // the box: owned layers and halos
    const std::int64_t bars = expectedBarCount(nx, ny, kHi - kLo);
    const double need = double(memoryEstimate(nx, ny, kHi - kLo));
    auto gigabytes = [](double bytes) {  // 3 digits, and no exponent: "0.25", "25.3", "1400"
        std::ostringstream g;
        if (bytes >= 1e11) g << std::fixed << std::setprecision(0);
        else g << std::setprecision(3);
        g << bytes / 1e9 << " GB";
        return g.str();
    };
    std::ostringstream msg;
    msg.precision(3);
    msg << "a lattice of " << nx << " x " << ny << " x " << kHi - kLo << " modules (" << bars
        << " bars) needs about " << gigabytes(need);
    if (have.bytes > 0 && need > have.bytes) {
        msg << "; " << have.what << " " << gigabytes(have.bytes);
        return msg.str();
    }
    // It fits in memory: only the node ids keep it from one process, and ranks on this machine can hold it.
    if (bars > std::int64_t(INT32_MAX)) {
        msg << ": too many for the 32-bit node ids of one process; split it over MPI ranks (mpirun -np P, P at most "
            << nz << ", the module layers)";
        return msg.str();
    }
    return "";
}

void checkFits(int nx, int ny, int nz, int k0, int k1) {
    if (const std::string why = latticeMisfit(nx, ny, nz, k0, k1, memoryLimit()); !why.empty())
        throw std::invalid_argument(why);
}

Lattice buildCubicLattice(int nx, int ny, int nz, double L0, const Material& m) {
    return buildLattice(nx, ny, nz, L0, m, {});
}

Lattice buildLattice(int nx, int ny, int nz, double L0, const Material& m,
                     const std::vector<std::uint8_t>& moduleMask) {
    return buildSlab(nx, ny, nz, L0, m, moduleMask, 0, nz);
}

Lattice buildSlab(int nx, int ny, int nz, double L0, const Material& m, const std::vector<std::uint8_t>& moduleMask,
                  int k0, int k1) {
    if (nx < 1 || ny < 1 || nz < 1)
        throw std::invalid_argument("a lattice needs at least one module per direction");
    if (!(L0 > 0) || !std::isfinite(L0))
        throw std::invalid_argument("module size L0 must be positive (got " + std::to_string(L0) + " m)");
    m.validate();
    const std::size_t modules = std::size_t(nx) * ny * nz;
    if (!moduleMask.empty() && moduleMask.size() != modules)
        throw std::invalid_argument("the module mask has " + std::to_string(moduleMask.size()) +
                                    " entries for " + std::to_string(modules) + " modules");
    if (!moduleMask.empty() && std::count(moduleMask.begin(), moduleMask.end(), 0) == std::ptrdiff_t(modules))
        throw std::invalid_argument("the module mask keeps no module");
    if (k0 < 0 || k1 > nz || k0 >= k1)
        throw std::invalid_argument("a slab owns module layers [k0, k1) with 0 <= k0 < k1 <= nz");
    checkFits(nx, ny, nz, k0, k1);  // the box's: an upper bound for a masked lattice
    const int kLo = std::max(k0 - 1, 0), kHi = std::min(k1 + 1, nz);  // the box: owned layers and halos

    Lattice lat;
    lat.nx = nx, lat.ny = ny, lat.nz = kHi - kLo, lat.L0 = L0;
    lat.moduleMask = moduleMask;
    lat.kOffset = kLo, lat.nzTotal = nz;
    lat.ownBegin = 2 * (k0 - kLo), lat.ownEnd = 2 * (k1 - kLo) + (k1 == nz ? 1 : 0);
    nz = lat.nz;  // from here on, the box
    lat.mass.assign(expectedNodeCount(nx, ny, nz), 0.0);
    const double moduleMass = m.rho * L0 * L0 * L0;
    InterruptCheck heardInMasses;
    for (int k = 0; k < nz; ++k, heardInMasses())
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                if (!lat.present(i, j, k)) continue;
                lat.mass[lat.centreId(i, j, k)] += 0.5 * moduleMass;
                for (int c = 0; c < 8; ++c)
                    lat.mass[lat.cornerId(i + (c & 1), j + (c >> 1 & 1), k + (c >> 2))] += moduleMass / 16.0;
            }

    // Nodes of no present module (mass 0) get invMass 0: with no bars and no
    // force they stay at rest, and they carry no kinetic energy.
    lat.invMass.resize(lat.mass.size());
    for (std::size_t i = 0; i < lat.mass.size(); ++i) lat.invMass[i] = lat.mass[i] > 0 ? 1.0 / lat.mass[i] : 0.0;

    // Families.
    const double An = normalBarArea(m.nu, L0), Ad = diagonalBarArea(m.nu, L0);
    const double Afn = normalFractureArea(m.ca, L0), Afd = diagonalFractureArea(m.ca, L0);
    const int n[3] = {nx, ny, nz};
    auto add = [&](BarKind kind, NodeKind a, NodeKind b, std::array<int, 3> off, std::array<int, 3> box, int axis,
                   std::array<double, 3> d0, double area, double Af) {
        const double L = std::sqrt(d0[0] * d0[0] + d0[1] * d0[1] + d0[2] * d0[2]);
        lat.families.push_back({kind, a, b, off, box, axis, d0, L, 1 / L, 1 / (L * L), m.E * area, Af});
    };
    for (int a = 0; a < 3; ++a) {  // edges along axis a: corner -> corner + e_a
        std::array<int, 3> off{0, 0, 0}, box{nx + 1, ny + 1, nz + 1};
        std::array<double, 3> d0{0, 0, 0};
        off[a] = 1, box[a] = n[a], d0[a] = L0;
        add(BarKind::Edge, NodeKind::Corner, NodeKind::Corner, off, box, a, d0, An, Afn);
    }
    for (int a = 0; a < 3; ++a) {  // centre -> centre + e_a
        std::array<int, 3> off{0, 0, 0}, box{nx, ny, nz};
        std::array<double, 3> d0{0, 0, 0};
        off[a] = 1, box[a] = n[a] - 1, d0[a] = L0;
        add(BarKind::CentreCentre, NodeKind::Centre, NodeKind::Centre, off, box, -1, d0, An, Afn);
    }
    for (int c = 0; c < 8; ++c) {  // centre (i,j,k) -> corner (i+di, j+dj, k+dk)
        const int di = c & 1, dj = c >> 1 & 1, dk = c >> 2;
        add(BarKind::Diagonal, NodeKind::Centre, NodeKind::Corner, {di, dj, dk}, {nx, ny, nz}, -1,
            {(di - 0.5) * L0, (dj - 0.5) * L0, (dk - 0.5) * L0}, Ad, Afd);
    }

    // Rows of bars, sorted by layer (then family, then y), numbered in that
    // order; a row's segments (see rowSegments) follow each other along x.
    auto layerOf = [](NodeKind kind, int k) { return 2 * k + (kind == NodeKind::Centre ? 1 : 0); };
    std::vector<std::tuple<int, int, int, int>> rows;  // (layer, family, q, r)
    for (int f = 0; f < int(lat.families.size()); ++f) {
        const BarFamily& fam = lat.families[f];
        if (fam.box[0] == 0) continue;
        for (int r = 0; r < fam.box[2]; ++r)
            for (int q = 0; q < fam.box[1]; ++q)
                rows.emplace_back(std::min(layerOf(fam.kindA, r), layerOf(fam.kindB, r + fam.offsetB[2])), f, q, r);
    }
    std::sort(rows.begin(), rows.end());
    // rowBarRows / rowLayer [f][q + box_y r]: the BarRows [first, end) of a row and its layer.
    std::vector<std::vector<std::pair<std::int32_t, std::int32_t>>> rowBarRows(lat.families.size());
    std::vector<std::vector<std::int32_t>> rowLayer(lat.families.size());
    for (std::size_t f = 0; f < lat.families.size(); ++f)
        rowBarRows[f].assign(std::size_t(lat.families[f].box[1]) * lat.families[f].box[2], {0, 0}),
            rowLayer[f].assign(rowBarRows[f].size(), -1);
    std::int64_t next = 0, layerFirst = 0;
    int currentLayer = -1;
    lat.barLayerStart.assign(lat.numLayers() + 1, 0);
    std::vector<double> shares;
    InterruptCheck heardInRows;
    for (const auto& [layer, f, q, r] : rows) {
        heardInRows();
        const BarFamily& fam = lat.families[f];
        if (layer != currentLayer) currentLayer = layer, layerFirst = next;
        shares.resize(fam.box[0]);
        for (int p = 0; p < fam.box[0]; ++p) shares[p] = barShare(lat, fam, p, q, r);
        const std::size_t qr = q + std::size_t(fam.box[1]) * r;
        rowBarRows[f][qr].first = std::int32_t(lat.barRows.size());
        rowLayer[f][qr] = layer;
        for (const auto& [p0, p1] : rowSegments(shares)) {
            BarRow row;
            row.first = next;
            row.inLayer = std::int32_t(next - layerFirst);
            row.nodeA = lat.nodeId(fam.kindA, p0, q, r);
            row.nodeB = lat.nodeId(fam.kindB, p0 + fam.offsetB[0], q + fam.offsetB[1], r + fam.offsetB[2]);
            row.count = p1 - p0;
            row.family = std::uint8_t(f);
            row.endShare = shares[p0];
            row.share = row.count >= 3 ? shares[p0 + 1] : row.endShare;
            next += row.count;
            lat.barRows.push_back(row);
            ++lat.barLayerStart[layer + 1];
        }
        rowBarRows[f][qr].second = std::int32_t(lat.barRows.size());
        lat.maxBarsInLayer = std::max(lat.maxBarsInLayer, std::int32_t(next - layerFirst));
    }
    for (int m = 0; m < lat.numLayers(); ++m) lat.barLayerStart[m + 1] += lat.barLayerStart[m];

    // Rows of nodes, layer by layer, with the bars that meet them in family
    // order: one incidence per segment, and a node lies in at most one
    // segment of a row, so its summation order does not depend on the mask.
    lat.nodeLayerStart.assign(lat.numLayers() + 1, 0);
    InterruptCheck heardInNodeRows;
    for (int m = 0; m < lat.numLayers(); ++m) {
        heardInNodeRows();
        const NodeKind kind = m % 2 ? NodeKind::Centre : NodeKind::Corner;
        const int k = m / 2, cx = kind == NodeKind::Corner ? nx + 1 : nx, cy = kind == NodeKind::Corner ? ny + 1 : ny;
        for (int j = 0; j < cy; ++j) {
            NodeRow row;
            row.first = lat.nodeId(kind, 0, j, k);
            row.count = cx;
            for (std::size_t f = 0; f < lat.families.size(); ++f) {
                const BarFamily& fam = lat.families[f];
                for (int end = 0; end < 2; ++end) {
                    if ((end == 0 ? fam.kindA : fam.kindB) != kind) continue;
                    const std::array<int, 3> o = end == 0 ? std::array<int, 3>{0, 0, 0} : fam.offsetB;
                    const int q = j - o[1], r = k - o[2];
                    if (q < 0 || q >= fam.box[1] || r < 0 || r >= fam.box[2]) continue;
                    const std::size_t qr = q + std::size_t(fam.box[1]) * r;
                    for (std::int32_t s = rowBarRows[f][qr].first; s < rowBarRows[f][qr].second; ++s) {
                        // node i meets bar p = i - o[0] of the row, p in [p0, p0 + count) for this segment
                        const BarRow& seg = lat.barRows[s];
                        const std::int32_t p0 = seg.nodeA - lat.nodeId(fam.kindA, 0, q, r);
                        row.incidences.push_back({rowLayer[f][qr], seg.inLayer - p0 - o[0], p0 + o[0],
                                                  p0 + seg.count + o[0], end == 0 ? 1.0 : -1.0});
                    }
                }
            }
            row.bulkBegin = 0, row.bulkEnd = row.count;
            for (const Incidence& in : row.incidences)
                row.bulkBegin = std::max(row.bulkBegin, in.begin), row.bulkEnd = std::min(row.bulkEnd, in.end);
            if (row.bulkEnd <= row.bulkBegin) row.bulkBegin = row.bulkEnd = 0;
            lat.nodeRows.push_back(std::move(row));
        }
        lat.nodeLayerStart[m + 1] = std::int32_t(lat.nodeRows.size());
    }
    return lat;
}

}  // namespace ldem
