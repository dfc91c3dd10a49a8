#include "ldem/Specimen.hpp"

#include <cmath>
#include <stdexcept>

#include "ldem/Slab.hpp"

namespace ldem {

Frequencies specimenFrequencies(const Lattice& lat, const Prescribed& pre) {
    Frequencies f = latticeFrequencies(lat, pre.mask);
    refuseMechanism(f);
    Field3 unitDrive(lat.numNodes());  // the prescribed DOFs at U = 1
    for (std::size_t k = 0; k < pre.node.size(); ++k) unitDrive[pre.dim[k]][pre.node[k]] = pre.weight[k];
    f.omegaDrive = driveFrequency(lat, pre.mask, unitDrive, &f.driveIterations);
    if (!(f.omegaDrive > 0)) f.omegaDrive = f.omega1;
    return f;
}

void Prescribed::follow(double U, double Ustart, double dt, Field3& u, Field3& v) const {
    for (std::size_t k = 0; k < node.size(); ++k)
        u[dim[k]][node[k]] = weight[k] * U, v[dim[k]][node[k]] = weight[k] * (U - Ustart) / dt;
}

// The sum of +u[b] and -u[a] is exact in either order.
double probeReading(const Lattice& lat, const Field3& u, const Probe& q) {
    std::int32_t nodes[2];
    double values[2];
    std::size_t n = 0;
    if (q.b >= 0) nodes[n] = q.b, values[n++] = u[q.dim][q.b];
    if (q.a >= 0) nodes[n] = q.a, values[n++] = -u[q.dim][q.a];
    return listSum(lat, n, [&](std::size_t k) { return nodes[k]; }, [&](std::size_t k) { return values[k]; });
}

double groupSum(const Lattice& lat, const std::vector<double>& f, const std::vector<std::int32_t>& nodes) {
    return listSum(lat, nodes.size(), [&](std::size_t k) { return nodes[k]; },
                   [&](std::size_t k) { return f[nodes[k]]; });
}

void Prescribed::add(std::int32_t n, int d, double w) {
    mask[n] |= std::uint8_t(1u << d);
    node.push_back(n), dim.push_back(std::uint8_t(d)), weight.push_back(w);
}

Prescribed makePrescribed(std::int64_t numNodes, const std::vector<std::int32_t>& node,
                          const std::vector<std::uint8_t>& dim, const std::vector<double>& weight) {
    if (dim.size() != node.size() || weight.size() != node.size())
        throw std::invalid_argument("specimen: the prescribed DOFs' arrays differ in length");
    Prescribed p;
    p.mask.assign(std::size_t(numNodes), 0);
    for (std::size_t k = 0; k < node.size(); ++k) {
        const std::string what = "node " + std::to_string(node[k]) + " direction " + std::to_string(dim[k]);
        if (node[k] < 0 || node[k] >= numNodes || dim[k] > 2)
            throw std::invalid_argument("specimen: a prescribed DOF names " + what + " (the lattice has " +
                                        std::to_string(numNodes) + " nodes, directions 0-2)");
        if (p.mask[node[k]] >> dim[k] & 1) throw std::invalid_argument("specimen: " + what + " is prescribed twice");
        if (!std::isfinite(weight[k])) throw std::invalid_argument("specimen: " + what + " has a weight not finite");
        p.add(node[k], dim[k], weight[k]);
    }
    return p;
}

void validate(const Specimen& s) {
    const std::int64_t n = s.lattice.numNodes();
    auto fail = [](const std::string& what) { throw std::invalid_argument("specimen: " + what); };
    auto checkNode = [&](std::int64_t id, const std::string& where) {
        if (id < 0 || id >= n) fail(where + " names node " + std::to_string(id) + " (the lattice has " +
                                    std::to_string(n) + " nodes)");
    };
    for (const auto& [name, nodes] : s.groups) {
        if (nodes.empty() && !s.lattice.isSlab()) fail("group '" + name + "' has no node");  // a slab may hold none
        for (auto id : nodes) checkNode(id, "group '" + name + "'");
    }
    const Prescribed& p = s.prescribed;
    if (p.mask.size() != std::size_t(n) || makePrescribed(n, p.node, p.dim, p.weight).mask != p.mask)
        fail("the prescribed mask does not match the prescribed DOFs");
    const Measures& m = s.measures;
    if (m.dim < 0 || m.dim > 2) fail("the measured direction must be 0, 1 or 2");
    if (!(m.area > 0) || !std::isfinite(m.area)) fail("the measured area must be positive");
    if (!(m.gaugeLength > 0) || !std::isfinite(m.gaugeLength)) fail("the gauge length must be positive");
    if (!(m.ligament >= 0) || !std::isfinite(m.ligament)) fail("the ligament must be positive (or 0: none)");
    if (!(m.meanDriveWeight != 0) || !std::isfinite(m.meanDriveWeight))
        fail("the loaded group is not driven along the measured direction (mean drive weight 0)");
    for (const Probe& q : m.probes) {
        if (q.a >= 0) checkNode(q.a, "probe '" + q.name + "'");
        if (q.b >= 0 || !s.lattice.isSlab()) checkNode(q.b, "probe '" + q.name + "'");  // -1: on another rank
        if (q.dim < 0 || q.dim > 2) fail("probe '" + q.name + "' has direction " + std::to_string(q.dim));
    }
    if (m.control < -1 || m.control >= int(m.probes.size()))
        fail("the controlled probe " + std::to_string(m.control) + " is not one of the " +
             std::to_string(m.probes.size()) + " probes");
    if (Comm::world().size() > 1 && !s.lattice.isSlab())
        throw std::invalid_argument("under mpirun, a specimen must be built as this rank's slab (specimenSlab)");
    for (const std::string& g : {m.support, m.loaded})
        if (!s.groups.count(g)) throw std::invalid_argument("the specimen's measures name no node group '" + g + "'");
}

const std::vector<std::int32_t>& nodeGroup(const std::map<std::string, std::vector<std::int32_t>>& groups,
                                           const std::string& name) {
    const auto it = groups.find(name);
    if (it == groups.end()) throw std::invalid_argument("the specimen has no node group '" + name + "'");
    return it->second;
}

Specimen specimenSlab(int nx, int ny, int nz, double L0, const Material& m,
                      const std::vector<std::uint8_t>& moduleMask,
                      const std::map<std::string, std::vector<std::int32_t>>& groups,
                      const std::vector<std::int32_t>& node, const std::vector<std::uint8_t>& dim,
                      const std::vector<double>& weight, const Measures& measures, std::pair<int, int> slab) {
    const std::int64_t whole = expectedNodeCount(nx, ny, nz);
    auto checked = [&](std::int32_t id, const std::string& where) {
        if (id < 0 || id >= whole)
            throw std::invalid_argument("specimen: " + where + " names node " + std::to_string(id) +
                                        " (the lattice has " + std::to_string(whole) + " nodes)");
        return id;
    };
    // Checked whole, so that every rank finds the same errors (a DOF listed twice, a bad direction or weight).
    makePrescribed(whole, node, dim, weight);
    Specimen s;
    const auto [k0, k1] = slab.second < 0 ? std::pair<int, int>{0, nz} : slab;
    s.lattice = buildSlab(nx, ny, nz, L0, m, moduleMask, k0, k1);
    const Lattice& lat = s.lattice;
    for (const auto& [name, ids] : groups) {
        if (ids.empty()) throw std::invalid_argument("specimen: group '" + name + "' has no node");
        std::vector<std::int32_t>& mine = s.groups[name];
        for (auto id : ids)
            if (const auto n = lat.localNode(checked(id, "group '" + name + "'")); n >= 0) mine.push_back(n);
    }
    std::vector<std::int32_t> localNode;
    std::vector<std::uint8_t> localDim;
    std::vector<double> localWeight;
    for (std::size_t k = 0; k < node.size(); ++k)
        if (const auto n = lat.localNode(checked(node[k], "a prescribed DOF")); n >= 0)
            localNode.push_back(n), localDim.push_back(dim[k]), localWeight.push_back(weight[k]);
    s.prescribed = makePrescribed(lat.numNodes(), localNode, localDim, localWeight);
    s.measures = measures;
    for (Probe& q : s.measures.probes) {
        q.b = lat.localNode(checked(q.b, "probe '" + q.name + "'"));
        if (q.a >= 0) q.a = lat.localNode(checked(q.a, "probe '" + q.name + "'"));
    }
    return s;
}

Specimen cubeTestSpecimen(const CubeTestParams& p) {
    const int n = p.geometry.modules();
    return cubeTestSpecimen(n, n, n, p.geometry.L0, p.material, p.loading, {}, worldSlab(n));
}

Specimen cubeTestSpecimen(int nx, int ny, int nz, double L0, const Material& m, const LoadingParams& p,
                          const std::vector<std::uint8_t>& moduleMask, std::pair<int, int> slab) {
    m.validate();
    p.validate();
    Specimen s;
    const auto [k0, k1] = slab.second < 0 ? std::pair<int, int>{0, nz} : slab;
    s.lattice = buildSlab(nx, ny, nz, L0, m, moduleMask, k0, k1);
    const Lattice& lat = s.lattice;
    Prescribed& c = s.prescribed;
    c.mask.assign(lat.numNodes(), 0);
    std::vector<std::int32_t>& bottomNodes = s.groups["bottom"];
    std::vector<std::int32_t>& topNodes = s.groups["top"];
    // Whether corner (i, j) of global plane k is a node of some present module.
    auto onFace = [&](int i, int j, int k) {
        for (int c = 0; c < 8; ++c)
            if (lat.present(i - (c & 1), j - (c >> 1 & 1), k - (c >> 2) - lat.kOffset)) return true;
        return false;
    };
    auto corner = [&](int i, int j, int k) {  // local id of a corner of global plane k, -1 if not here
        return lat.localNode(i + std::int64_t(nx + 1) * (j + std::int64_t(ny + 1) * k));
    };
    const double width = lat.nx * lat.L0;
    double weightSum = 0;
    int faceNodes = 0;
    for (int j = 0; j <= lat.ny; ++j)
        for (int i = 0; i <= lat.nx; ++i) {
            if (!onFace(i, j, 0) || !onFace(i, j, nz)) continue;  // outside a clipped prism's faces
            // Upper face: triangular varies linearly in x from 0 to 1.
            const double w = p.shape == LoadShape::Uniform ? 1.0 : (i * lat.L0) / width;
            weightSum += w, ++faceNodes;
            const auto bottom = corner(i, j, 0), top = corner(i, j, nz);
            if (bottom >= 0) {  // on this rank (its slab holds the lowest layer)
                bottomNodes.push_back(bottom);
                // Lower face: vertical DOF fixed; lateral fixed, or on rollers with only
                // the rigid-body motion pinned (x, y at one corner, y at the next).
                c.add(bottom, 2, 0.0);
                const bool pin = (i == 0 && j == 0) || (i == lat.nx && j == 0);
                if (!p.bottomLateralFree || pin) {
                    if (!p.bottomLateralFree || i == 0) c.add(bottom, 0, 0.0);
                    c.add(bottom, 1, 0.0);
                }
            }
            if (top >= 0) {
                topNodes.push_back(top);
                if (!p.topLateralFree) c.add(top, 0, 0.0), c.add(top, 1, 0.0);
                c.add(top, 2, w);
            }
        }
    Measures& ms = s.measures;
    ms.support = "bottom", ms.loaded = "top", ms.dim = 2;
    ms.area = lat.nx * lat.L0 * lat.ny * lat.L0;
    if (!moduleMask.empty()) {  // the lower face's own modules
        int kept = 0;
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) kept += lat.present(i, j, -lat.kOffset);
        ms.area = kept * L0 * L0;
    }
    ms.ligament = ms.area;  // the cube breaks across its section
    ms.gaugeLength = nz * lat.L0;
    ms.meanDriveWeight = weightSum / faceNodes;
    return s;
}

}  // namespace ldem
