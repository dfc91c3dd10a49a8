// A specimen is data (Specimen.hpp): Simulation reads the stress, the strain
// and the separation from the groups its measures name, in any direction.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "ldem/Simulation.hpp"
#include "ldem/Specimen.hpp"

using namespace ldem;

namespace {
// The cube test's prism of 4 x 2 x 2 modules turned on its side: held at
// x = 0 (all three DOFs), pulled along x at x = 4 L0, lateral DOFs free.
Specimen prismPulledAlongX(const Material& m) {
    Specimen s;
    s.lattice = buildCubicLattice(4, 2, 2, 0.02, m);
    const Lattice& lat = s.lattice;
    s.prescribed.mask.assign(lat.numNodes(), 0);
    for (int k = 0; k <= lat.nz; ++k)
        for (int j = 0; j <= lat.ny; ++j) {
            const auto held = lat.cornerId(0, j, k), pulled = lat.cornerId(lat.nx, j, k);
            s.groups["held"].push_back(held), s.groups["pulled"].push_back(pulled);
            for (int d = 0; d < 3; ++d) s.prescribed.add(held, d, 0.0);
            s.prescribed.add(pulled, 0, 1.0);
        }
    s.measures = {"held", "pulled", 0, lat.ny * lat.L0 * lat.nz * lat.L0, lat.nx * lat.L0, 1.0};
    return s;
}
// The prescribed DOFs of a group's nodes as (node, dim, weight), in a set.
std::set<std::tuple<std::int32_t, int, double>> prescribedOn(const Specimen& s, const std::string& group) {
    const std::vector<std::int32_t>& nodes = s.groups.at(group);
    const std::set<std::int32_t> in(nodes.begin(), nodes.end());
    std::set<std::tuple<std::int32_t, int, double>> out;
    const Prescribed& p = s.prescribed;
    for (std::size_t k = 0; k < p.node.size(); ++k)
        if (in.count(p.node[k])) out.emplace(p.node[k], p.dim[k], p.weight[k]);
    return out;
}
}  // namespace

// Direct checks (run first by tests/mutation/run.py): the probe, U_min, the
// triangular drive's profile and the rollers, each against hand values.

// A probe reads u_b - u_a: on the 2 x 2 x 2 cube pulled at 0.1/s, the top
// corner (0, 0) against the bottom one (u = 0) reads the drive U = mean strain x
// height (uniform load); the top corner against the first module's
// centre node reads their difference, positive (the top moves most) and
// below U; a probe with no node a reads u_b alone. Exact (the sum of two
// terms), the drive to round-off (1e-15 relative).
TEST(DirectSpecimen, ProbeReadsUbMinusUa) {
    Material m;
    LoadingParams lp;
    lp.strainRate = 0.1;
    RunParams rp;
    rp.threads = 1, rp.recordEvery = 50;
    Specimen s = cubeTestSpecimen(2, 2, 2, 0.02, m, lp);
    const Lattice& lat = s.lattice;
    const std::int32_t top = lat.cornerId(0, 0, 2), bottom = lat.cornerId(0, 0, 0), centre = lat.centreId(0, 0, 0);
    s.measures.probes = {{"across", bottom, top, 2}, {"inner", centre, top, 2}, {"alone", -1, centre, 2}};
    const double height = 2 * 0.02;
    Simulation sim(std::move(s), m, lp, rp);
    int records = 0;
    sim.run([&](const CurvePoint& p) {
        const Field3& u = sim.displacements();
        EXPECT_EQ(p.probes.at(0), u.z[top]) << "record " << records;  // u.z[bottom] = 0
        EXPECT_NEAR(u.z[top], p.meanStrain * height, 1e-15 * u.z[top]) << "record " << records;
        EXPECT_EQ(p.probes.at(1), u.z[top] - u.z[centre]) << "record " << records;
        EXPECT_EQ(p.probes.at(2), u.z[centre]) << "record " << records;
        return ++records < 10;
    });
    ASSERT_EQ(records, 10);
    const Field3& u = sim.displacements();
    EXPECT_GT(u.z[centre], 0.0);
    EXPECT_GT(u.z[top] - u.z[centre], 0.0);
    EXPECT_LT(u.z[top] - u.z[centre], u.z[top]);
}

// U_min = E[G_f] x the face's area: 3 x 2 modules of 0.02 m, 6 L0^2 (not the
// (n+1)^2 L0^2 of the face's nodes). Round-off (1e-15 relative).
TEST(DirectSpecimen, MinFractureEnergyIsGfTimesTheCrossSection) {
    Material m;
    m.GfMean = 80.0;
    RunParams rp;
    rp.threads = 1;
    const double L0 = 0.02, area = 3 * L0 * 2 * L0;
    const LoadingParams lp;
    const Simulation sim(cubeTestSpecimen(3, 2, 2, L0, m, lp), m, lp, rp);
    EXPECT_NEAR(sim.measures().area, area, 1e-15 * area);
    EXPECT_NEAR(sim.minFractureEnergy(), 80.0 * area, 1e-15 * 80.0 * area);
}

// The triangular drive moves the top node at x by U x / width: zero at x = 0,
// U at the opposite edge, mean U/2 over the face's nodes (0, 1/4, ..., 1 along
// x: mean exactly 1/2), so the most-pulled edge moves twice the mean. The
// specimen's mean drive weight is that mean. Exact to round-off (1e-15).
TEST(DirectSpecimen, TriangularDriveProfile) {
    Material m;
    LoadingParams lp;
    lp.shape = LoadShape::Triangular;
    const double L0 = 0.02;
    const Specimen s = cubeTestSpecimen(4, 3, 2, L0, m, lp);
    const auto x = nodePositions(s.lattice);
    const auto top = prescribedOn(s, "top");
    ASSERT_EQ(top.size(), 5u * 4u);  // z only: the top is laterally free by default
    double sum = 0, lowest = 1, highest = 0;
    for (const auto& [n, d, w] : top) {
        EXPECT_EQ(d, 2);
        EXPECT_NEAR(w, x[0][n] / (4 * L0), 1e-15) << "node " << n;
        sum += w, lowest = std::min(lowest, w), highest = std::max(highest, w);
    }
    EXPECT_EQ(lowest, 0.0);
    EXPECT_NEAR(highest, 1.0, 1e-15);
    EXPECT_NEAR(sum / top.size(), 0.5, 1e-15);
    EXPECT_NEAR(s.measures.meanDriveWeight, 0.5, 1e-15);
}

// On rollers the lower face holds z everywhere and only the rigid motion
// otherwise: x and y at corner (0, 0), y at corner (nx, 0); held laterally,
// x, y and z at every node. Checked on the prescribed DOFs of a 3 x 2 face
// (so (nx, 0), (0, ny) and (nx, ny) differ). Exact.
TEST(DirectSpecimen, RollersHoldExactlyTheirDofs) {
    Material m;
    const int nx = 3, ny = 2;
    for (bool rollers : {true, false}) {
        LoadingParams lp;
        lp.bottomLateralFree = rollers;
        const Specimen s = cubeTestSpecimen(nx, ny, 2, 0.02, m, lp);
        const Lattice& lat = s.lattice;
        std::set<std::tuple<std::int32_t, int, double>> want;
        for (int j = 0; j <= ny; ++j)
            for (int i = 0; i <= nx; ++i) {
                want.emplace(lat.cornerId(i, j, 0), 2, 0.0);
                if (!rollers) want.emplace(lat.cornerId(i, j, 0), 0, 0.0), want.emplace(lat.cornerId(i, j, 0), 1, 0.0);
            }
        if (rollers)
            want.emplace(lat.cornerId(0, 0, 0), 0, 0.0), want.emplace(lat.cornerId(0, 0, 0), 1, 0.0),
                want.emplace(lat.cornerId(nx, 0, 0), 1, 0.0);
        EXPECT_EQ(prescribedOn(s, "bottom"), want) << (rollers ? "rollers" : "held");
        EXPECT_EQ(s.groups.at("bottom").size(), std::size_t((nx + 1) * (ny + 1)));
    }
}

TEST(Specimen, APrismPulledAlongXIsTheCubeTestsPrismPulledAlongZ) {
    Material m;
    m.GfCV = 0;  // every bar alike: the two lattices are the same up to a rotation
    RunParams rp;
    rp.threads = 1, rp.stopAt = stopNamed("load_loss"), rp.recordEvery = 25;  // 40 records: 1000 steps of 0.8 of the limit
    LoadingParams lp;
    lp.strainRate = 0.1;
    Simulation alongX(prismPulledAlongX(m), m, lp, rp);
    Simulation alongZ(cubeTestSpecimen(2, 2, 4, 0.02, m, lp), m, lp, rp);
    EXPECT_NEAR(alongX.frequencies().omegaMax, alongZ.frequencies().omegaMax, 1e-9 * alongZ.frequencies().omegaMax);
    EXPECT_NEAR(alongX.frequencies().omega1, alongZ.frequencies().omega1, 1e-6 * alongZ.frequencies().omega1);
    EXPECT_NEAR(alongX.dt(), alongZ.dt(), 1e-9 * alongZ.dt());
    std::vector<CurvePoint> x, z;
    alongX.run([&](const CurvePoint& p) { x.push_back(p); return x.size() < 40; });
    alongZ.run([&](const CurvePoint& p) { z.push_back(p); return z.size() < 40; });
    ASSERT_EQ(x.size(), z.size());
    double peak = 0;
    for (const auto& p : z) peak = std::max(peak, p.stress);
    ASSERT_GT(peak, 1e6);  // a real load, up to the elastic range's end
    for (std::size_t i = 0; i < x.size(); ++i) {
        EXPECT_NEAR(x[i].meanStrain, z[i].meanStrain, 1e-9 * z[i].meanStrain);  // dt: Lanczos to rounding
        EXPECT_NEAR(x[i].stress, z[i].stress, 1e-9 * peak) << "record " << i;
        EXPECT_NEAR(x[i].stressLoaded, z[i].stressLoaded, 1e-9 * peak) << "record " << i;
        EXPECT_NEAR(x[i].elastic, z[i].elastic, 1e-9 * (z[i].elastic + 1e-30)) << "record " << i;
    }
}

TEST(Specimen, MeasuresMustNameItsGroups) {
    Material m;
    Specimen s = prismPulledAlongX(m);
    s.measures.support = "base";
    try {
        Simulation sim(std::move(s), m, LoadingParams{}, RunParams{});
        ADD_FAILURE() << "accepted a measure on a missing group";
    } catch (const std::invalid_argument& e) {
        EXPECT_STREQ(e.what(), "the specimen's measures name no node group 'base'");
    }
}

TEST(Specimen, AFullMaskIsTheCubeTestAndAClippedPrismStandsOnItsOwnFace) {
    Material m;
    LoadingParams lp;
    lp.strainRate = 0.1;
    RunParams rp;
    rp.threads = 1, rp.stopAt = stopNamed("load_loss"), rp.recordEvery = 25;  // 40 records: 1000 steps of 0.8 of the limit
    const std::vector<std::uint8_t> ones(3 * 3 * 3, 1);
    Simulation full(cubeTestSpecimen(3, 3, 3, 0.02, m, lp, ones), m, lp, rp), cube(cubeTestSpecimen(3, 3, 3, 0.02, m, lp), m, lp, rp);
    EXPECT_DOUBLE_EQ(full.measures().area, cube.measures().area);
    std::vector<CurvePoint> a, b;
    full.run([&](const CurvePoint& p) { a.push_back(p); return a.size() < 30; });
    cube.run([&](const CurvePoint& p) { b.push_back(p); return b.size() < 30; });
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i].stress, b[i].stress, 1e-12 * std::abs(b[i].stress));
    // An L-shaped prism (3 of 4 columns of modules kept): its faces are its own
    // nodes, its area its 3 modules.
    std::vector<std::uint8_t> L(2 * 2 * 3, 1);
    for (int k = 0; k < 3; ++k) L[1 + 2 * (1 + 2 * k)] = 0;
    const Specimen s = cubeTestSpecimen(2, 2, 3, 0.02, m, lp, L);
    EXPECT_DOUBLE_EQ(s.measures.area, 3 * 0.02 * 0.02);
    EXPECT_EQ(s.groups.at("bottom").size(), 8u);  // 9 corners of the 2 x 2 face but the one of no module
    for (auto n : s.groups.at("top")) EXPECT_GT(s.lattice.mass[n], 0);
}

TEST(Specimen, APushIsMeasuredPositive) {
    // The 2 x 2 x 4 cube test's prism, its upper face pushed instead of pulled:
    // stress and strain positive in the sense of the drive (compression).
    Material m;
    LoadingParams lp;
    lp.strainRate = 0.1;
    RunParams rp;
    rp.threads = 1, rp.recordEvery = 10;
    Specimen pushed = cubeTestSpecimen(2, 2, 4, 0.02, m, lp);
    for (double& w : pushed.prescribed.weight) w = -w;
    pushed.measures.meanDriveWeight = -pushed.measures.meanDriveWeight;
    Simulation push(std::move(pushed), m, lp, rp), pull(cubeTestSpecimen(2, 2, 4, 0.02, m, lp), m, lp, rp);
    std::vector<CurvePoint> a, b;
    // Records to 0.6 eps_p, below any bar's peak strain at any time step.
    const auto belowPeak = [&](std::vector<CurvePoint>& out) {
        return [&](const CurvePoint& p) { out.push_back(p); return p.meanStrain < 0.6 * m.epsP; };
    };
    push.run(belowPeak(a));
    pull.run(belowPeak(b));
    ASSERT_EQ(a.size(), b.size());
    EXPECT_GT(a.back().stress, 1e5);
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].meanStrain, b[i].meanStrain);
        // Below eps_p the lattice is linear: the push is the pull mirrored (up to the geometric nonlinearity).
        EXPECT_NEAR(a[i].stress, b[i].stress, 2e-3 * std::abs(b.back().stress)) << "record " << i;
    }
}

TEST(Specimen, ValidateNamesWhatIsWrong) {
    auto message = [](auto f) {
        try {
            f();
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_EQ(message([] { makePrescribed(4, {1, 1}, {2, 2}, {0.0, 1.0}); }),
              "specimen: node 1 direction 2 is prescribed twice");
    EXPECT_NE(message([] { makePrescribed(4, {7}, {0}, {0.0}); }).find("names node 7 direction 0"), std::string::npos);
    Material m;
    Specimen s = cubeTestSpecimen(2, 2, 2, 0.02, m, LoadingParams{});
    s.groups["top"].push_back(999999);
    EXPECT_EQ(message([&] { validate(s); }), "specimen: group 'top' names node 999999 (the lattice has 35 nodes)");
    s = cubeTestSpecimen(2, 2, 2, 0.02, m, LoadingParams{});
    s.measures.probes.push_back({"tip", -1, 35, 2});
    EXPECT_EQ(message([&] { validate(s); }), "specimen: probe 'tip' names node 35 (the lattice has 35 nodes)");
}

// The servo of opening control (Loading.hpp): the velocity that opens the mouth
// at the program's rate with the secant ratio, the lag corrected at rate g, the
// actuator's limit, and the smooth start.
TEST(Servo, OpensAtTheProgramsRateWithinTheActuatorsLimit) {
    Drive program;  // the actuator: its speed limit and its ramp
    program.v0 = 2e-3, program.rampTime = 0.01;
    Servo s;
    s.rate = 1e-3, s.gain = 50;
    s.U = 1e-5;
    const double t = 0.1, onProgram = s.rate * (t - 0.5 * program.rampTime);  // c*(t) past the ramp
    EXPECT_DOUBLE_EQ(s.velocity(t, onProgram, program), s.rate / (onProgram / s.U));  // r / a, a = c/U
    const double behind = onProgram - 1e-6;  // lagging by 1 um: g x 1 um more opening rate
    EXPECT_DOUBLE_EQ(s.velocity(t, behind, program), (s.rate + s.gain * 1e-6) / (behind / s.U));
    s.U = 1e-3;  // a tiny ratio: the demand exceeds the actuator's speed, which caps it
    EXPECT_DOUBLE_EQ(s.velocity(t, onProgram, program), program.v0);
    EXPECT_DOUBLE_EQ(s.velocity(t, 10 * onProgram, program), -program.v0);  // the mouth far ahead: back off
    s.U = 0;  // nothing moved yet: the ratio is unknown, the drive goes at the ramped limit
    EXPECT_DOUBLE_EQ(s.velocity(0.5 * program.rampTime, 0.0, program), 0.5 * program.v0);
    EXPECT_DOUBLE_EQ(s.velocity(0.0, 0.0, program), 0.0);  // at rest at t = 0
    s.advance(1e-4, 0.0, 0.0, program);                     // velocity at mid-step
    EXPECT_DOUBLE_EQ(s.Uprev, 0.0);
    EXPECT_DOUBLE_EQ(s.U, 1e-4 * s.velocity(0.5e-4, 0.0, program));
}
