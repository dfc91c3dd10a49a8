// Python bindings of the C++ core: ldem._core. Thin: parameters, the
// Simulation with its time-step loop (run without the GIL, calling back into
// Python once per record), and numpy views of the lattice and its state.
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <thread>

#include "ldem/Integrator.hpp"
#include "ldem/Interrupt.hpp"
#include "ldem/Lattice.hpp"
#include "ldem/Loading.hpp"
#include "ldem/Material.hpp"
#include "ldem/MaxFlow.hpp"
#include "ldem/Modal.hpp"
#include "ldem/ParameterTable.hpp"
#include "ldem/Parallel.hpp"
#include "ldem/RandomField.hpp"
#include "ldem/Separation.hpp"
#include "ldem/Comm.hpp"
#include "ldem/Relations.hpp"
#include "ldem/Slab.hpp"
#include "ldem/Simulation.hpp"
#include "ldem/Specimen.hpp"
#include "ldem/laws/Registry.hpp"

namespace py = pybind11;
using namespace ldem;

namespace {
template <class T>
py::array_t<T> toNumpy(const std::vector<T>& v) {
    return py::array_t<T>(py::ssize_t(v.size()), v.data());
}

// A numpy array (or anything array-like) as a vector of T, copied at once: not
// element by element, as a std::vector argument or a list would be.
template <class T>
std::vector<T> fromNumpy(const py::handle& a) {
    const auto arr = py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(a);
    if (!arr) throw py::type_error("expected an array of numbers");
    return {arr.data(), arr.data() + arr.size()};
}

py::array_t<double> eventArray(const RunEvent& e) {
    return toNumpy(std::vector<double>{double(e.step), e.time, e.meanStrain, e.fracture});
}

RunEvent eventOf(const py::handle& a) {
    const auto v = fromNumpy<double>(a);
    return {std::int64_t(v.at(0)), v.at(1), v.at(2), v.at(3)};
}

// A checkpoint as named numpy arrays (the keys of checkpoint.npz, README);
// each dynamic part's state is one array, "part_" + its name.
py::dict checkpointDict(const Checkpoint& c) {
    py::dict d;
    for (auto [name, f] : {std::pair<const char*, const Field3*>{"u", &c.u}, {"v", &c.v}, {"f", &c.f}}) {
        d[(std::string(name) + "_x").c_str()] = toNumpy(f->x);
        d[(std::string(name) + "_y").c_str()] = toNumpy(f->y);
        d[(std::string(name) + "_z").c_str()] = toNumpy(f->z);
    }
    for (const auto& [name, values] : c.bars) d[name.c_str()] = toNumpy(values);  // the law's (kappa, eps_r, ...)
    d["softening"] = toNumpy(c.softening);
    const RunProgress& g = c.progress;
    const RunSummary& s = g.summary;
    d["scalars"] = toNumpy(std::vector<double>{c.time, c.externalWork, c.dampingWork, g.maxEnergy, g.maxResidual,
                                               s.peakStress, s.strainAtPeak, s.edgeStrainAtPeak, s.fractureEnergy,
                                               s.driveStepOverEpsP});
    d["counters"] = toNumpy(std::vector<std::int64_t>{c.step, s.steps});
    d["load_loss"] = eventArray(s.loadLoss), d["separation"] = eventArray(s.separation);
    d["converged"] = eventArray(s.converged);
    for (const auto& [name, state] : c.parts) d[("part_" + name).c_str()] = toNumpy(state);
    return d;
}

Checkpoint checkpointOf(const Simulation& sim, const py::dict& d) {
    if (!d.contains("part_test_load_loss"))
        throw std::invalid_argument("a checkpoint of an older ldem (before its dynamic parts): run the case again");
    Checkpoint c;
    for (auto [name, f] : {std::pair<const char*, Field3*>{"u", &c.u}, {"v", &c.v}, {"f", &c.f}}) {
        f->x = fromNumpy<double>(d[(std::string(name) + "_x").c_str()]);
        f->y = fromNumpy<double>(d[(std::string(name) + "_y").c_str()]);
        f->z = fromNumpy<double>(d[(std::string(name) + "_z").c_str()]);
    }
    std::visit([&](const auto& law) {
        for (const auto& [name, values] : law.arrays()) c.bars.emplace_back(name, fromNumpy<double>(d[name.c_str()]));
    }, sim.law());
    c.softening = fromNumpy<std::uint8_t>(d["softening"]);
    const auto sc = fromNumpy<double>(d["scalars"]);
    const auto ct = fromNumpy<std::int64_t>(d["counters"]);
    RunProgress& g = c.progress;
    RunSummary& s = g.summary;
    c.time = sc.at(0), c.externalWork = sc.at(1), c.dampingWork = sc.at(2);
    g.maxEnergy = sc.at(3), g.maxResidual = sc.at(4);
    s.peakStress = sc.at(5), s.strainAtPeak = sc.at(6), s.edgeStrainAtPeak = sc.at(7), s.fractureEnergy = sc.at(8);
    s.driveStepOverEpsP = sc.at(9);
    c.step = ct.at(0), s.steps = ct.at(1);
    s.loadLoss = eventOf(d["load_loss"]), s.separation = eventOf(d["separation"]), s.converged = eventOf(d["converged"]);
    for (const std::string& name : sim.partNames()) {  // restore() checks that they are this set-up's
        const std::string key = "part_" + name;
        if (d.contains(key.c_str())) c.parts.emplace_back(name, fromNumpy<double>(d[key.c_str()]));
    }
    g.started = true;
    return c;
}

}  // namespace

PYBIND11_MODULE(_core, m) {
    m.doc() = "ldem C++ core: truss-like lattice DEM (Riera-Iturrioz) for brittle fracture";

    py::register_exception<InstabilityError>(m, "InstabilityError", PyExc_RuntimeError);

    // Ctrl-C and SIGTERM heard inside the core's long loops (Interrupt.hpp):
    // Python's handlers run under the GIL, and the exception one raises
    // (KeyboardInterrupt, ldem.signals.Terminated) is thrown on through the
    // loop. Only the main thread runs Python's handlers: elsewhere the poll
    // takes no GIL.
    static std::thread::id mainThread;
    const py::module_ threading = py::module_::import("threading");
    if (threading.attr("current_thread")().is(threading.attr("main_thread")()))
        mainThread = std::this_thread::get_id();
    setInterruptPoll([] {
        if (std::this_thread::get_id() != mainThread) return;
        py::gil_scoped_acquire gil;
        if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    });

    // Under mpirun, MPI starts at the first use of the ranks (a cube's
    // Simulation: each rank builds and runs only its slab, pkg/ldem/Slab.hpp)
    // and ends with the interpreter.
    py::module_::import("atexit").attr("register")(py::cpp_function([] { mpiFinalize(); }));
    m.def("mpi_rank", [] { return Comm::world().rank(); }, "this process's MPI rank (0 without mpirun)");
    m.def("mpi_ranks", [] { return Comm::world().size(); }, "the number of MPI ranks (1 without mpirun)");
    m.def("mpi_launched", &mpiLaunched, "whether this process was started by mpirun");
    m.def("mpi_available", &mpiAvailable, "whether this build of ldem can run under MPI");
    m.def("mpi_gather_bytes", [](const py::bytes& b) {
        // Every rank's bytes on rank 0, in rank order (empty list elsewhere): small outputs (crack pictures).
        const std::string str = b;
        const std::vector<std::int64_t> mine(str.begin(), str.end());
        std::vector<std::int64_t> sizes = Comm::world().gather({std::int64_t(mine.size())});
        const std::vector<std::int64_t> all = Comm::world().gather(mine);
        py::list out;
        std::size_t at = 0;
        for (std::int64_t n : sizes) {
            std::string piece(std::size_t(n), '\0');
            for (std::int64_t k = 0; k < n; ++k) piece[std::size_t(k)] = char(all[at++]);
            out.append(py::bytes(piece));
        }
        return out;
    }, py::arg("data"));

    // The parameters: one table (pkg/ldem/Parameters.hpp); each struct's
    // attributes, their defaults and checks are read from it.
    m.def(
        "parameter_table",
        [] {
            py::list rows;
            for (const ParamInfo& p : cubeTestParameters()) {
                py::dict d;
                d["group"] = p.group, d["name"] = p.name, d["unit"] = p.unit, d["help"] = p.help;
                d["kind"] = p.kind, d["default"] = p.defaultValue, d["domain"] = p.domain.describe();
                d["choices"] = p.domain.names;
                rows.append(d);
            }
            return rows;
        },
        "every parameter of a cube test: group, name, unit, help, kind (float/int/choice), default, domain, choices");
    auto byName = [](const std::vector<std::pair<std::string, ParamValue>>& own) {
        py::dict d;
        for (const auto& [name, value] : own) d[py::str(name)] = value;
        return d;
    };
    m.def("cube_own_defaults", [=] { return byName(cubeOwnDefaults()); },
          "the cube's own defaults over the table's (ldem.CubeTest, ldem cube): its paced drive");
    m.def("specimen_own_defaults", [=] { return byName(specimenOwnDefaults()); },
          "a specimen file's own defaults over the table's (ldem run): its rate from its own period, rule (c)");
    // A group's struct: Material(E=..., nu=...) with its parameters as keyword
    // arguments, each an attribute with its help, validate(), and a repr.
    auto groupStruct = [&](auto cls, const std::string& group) {
        using T = typename decltype(cls)::type;
        std::vector<std::string> names;
        for (const ParamInfo& p : cubeTestParameters())
            if (p.group == group) names.push_back(p.name);
        cls.def(py::init([](const py::kwargs& kw) {
                    T s;
                    for (const auto& item : kw) setParameter(s, py::cast<std::string>(item.first),
                                                             py::cast<ParamValue>(item.second));
                    return s;
                }),
                "every parameter of the group as a keyword argument; unset ones at their defaults")
            .def("validate", &T::validate, "raises ValueError naming the first parameter outside its domain")
            .def("__repr__", [names, cls](const T& s) {
                std::string r = py::cast<std::string>(cls.attr("__name__")) + "(";
                for (std::size_t i = 0; i < names.size(); ++i)
                    r += (i ? ", " : "") + names[i] + "=" + py::cast<std::string>(py::repr(py::cast(getParameter(s, names[i]))));
                return r + ")";
            });
        for (const ParamInfo& p : cubeTestParameters())
            if (p.group == group) {
                const std::string name = p.name;
                cls.def_property(
                    name.c_str(), [name](const T& s) { return getParameter(s, name); },
                    [name](T& s, const ParamValue& v) { setParameter(s, name, v); },
                    (p.help + (p.unit.empty() ? "" : " [" + p.unit + "]") + "; " + p.domain.describe()).c_str());
            }
    };
    groupStruct(py::class_<Material>(m, "Material", "material constants (pkg/ldem/Parameters.hpp)"), "material");
    groupStruct(py::class_<LoadingParams>(m, "LoadingParams", "the loading of a cube test"), "loading");
    groupStruct(py::class_<RunParams>(m, "RunParams", "how a run goes: seed, damping, time step, stop rules"), "run");
    py::class_<CubeTestParams>(m, "CubeTestParams", "every parameter of a cube test, by name: p['nu'] = 0.2")
        .def(py::init<>())
        .def("__getitem__", [](const CubeTestParams& p, const std::string& k) { return getParameter(p, k); })
        .def("__setitem__", [](CubeTestParams& p, const std::string& k, const ParamValue& v) { setParameter(p, k, v); })
        .def("validate", &CubeTestParams::validate)
        .def("modules", [](const CubeTestParams& p) { return p.geometry.modules(); })
        .def_readonly("material", &CubeTestParams::material)
        .def_readonly("loading", &CubeTestParams::loading)
        .def_readonly("run", &CubeTestParams::run);

    py::class_<CurvePoint>(m, "CurvePoint", "one record of a run: state n (stresses in Pa, energies in J)")
        .def("__repr__", [](const CurvePoint& p) {
            return "CurvePoint(step=" + std::to_string(p.step) + ", mean_strain=" + formatNumber(p.meanStrain) +
                   ", stress=" + formatNumber(p.stress) + " Pa, fracture=" + formatNumber(p.fracture) +
                   " J, broken=" + std::to_string(p.broken) + ")";
        })
        .def_readonly("step", &CurvePoint::step)
        .def_readonly("time", &CurvePoint::time)
        .def_readonly("mean_strain", &CurvePoint::meanStrain)
        .def_readonly("stress", &CurvePoint::stress, "reactions of the support group / area [Pa]")
        .def_readonly("stress_loaded", &CurvePoint::stressLoaded, "the same on the loaded group, negated [Pa]")
        .def_readonly("external_work", &CurvePoint::externalWork)
        .def_readonly("kinetic", &CurvePoint::kinetic)
        .def_readonly("kinetic_own", &CurvePoint::kineticOwn,
                      "the kinetic energy less the drive's quasi-static motion, 1/2 sum m |v - (U'/U) u|^2 [J]")
        .def_readonly("elastic", &CurvePoint::elastic)
        .def_readonly("fracture", &CurvePoint::fracture)
        .def_readonly("damping", &CurvePoint::damping)
        .def_readonly("damaged", &CurvePoint::damaged)
        .def_readonly("broken", &CurvePoint::broken)
        .def_readonly("probes", &CurvePoint::probes, "the specimen's probes, in their order [m]");

    py::class_<RunEvent>(m, "RunEvent", "an event of the run: step (-1: not reached), time, mean strain, fracture energy")
        .def_readonly("step", &RunEvent::step)
        .def_readonly("time", &RunEvent::time)
        .def_readonly("mean_strain", &RunEvent::meanStrain)
        .def_readonly("fracture", &RunEvent::fracture)
        .def_property_readonly("reached", &RunEvent::reached);
    py::class_<RunSummary>(m, "RunSummary", "what Simulation.run returns: the peak, the events, the energy check")
        .def("__repr__", [](const RunSummary& s) {
            return "RunSummary(peak_stress=" + formatNumber(s.peakStress) + " Pa, strain_at_peak=" +
                   formatNumber(s.strainAtPeak) + ", stop_reason='" + s.stopReason + "', steps=" +
                   std::to_string(s.steps) + ")";
        })
        .def_readonly("peak_stress", &RunSummary::peakStress)
        .def_readonly("strain_at_peak", &RunSummary::strainAtPeak)
        .def_readonly("edge_strain_at_peak", &RunSummary::edgeStrainAtPeak)
        .def_readonly("load_loss", &RunSummary::loadLoss)
        .def_readonly("separation", &RunSummary::separation)
        .def_readonly("converged", &RunSummary::converged)
        .def_readonly("fracture_energy", &RunSummary::fractureEnergy)
        .def_readonly("energy_balance_error", &RunSummary::energyBalanceError)
        .def_readonly("energy_error", &RunSummary::energyError)
        .def_readonly("steps", &RunSummary::steps)
        .def_readonly("drive_step_over_eps_p", &RunSummary::driveStepOverEpsP)
        .def_readonly("drive_periods_to_eps_p", &RunSummary::drivePeriodsToEpsP,
                      "N of rule (c): the periods 2 pi/omega_d the drive takes to strain eps_p")
        .def_readonly("drive_strain_rate", &RunSummary::driveStrainRate,
                      "the strain rate driven [1/s]: strain_rate, or eps_p omega_d / (2 pi rate_periods)")
        .def_readonly("kinetic_over_work_at_peak", &RunSummary::kineticOverWorkAtPeak)
        .def_readonly("quasi_static_flagged", &RunSummary::quasiStaticFlagged)
        .def_readonly("stop_reason", &RunSummary::stopReason);
    m.attr("DRIVE_STEP_LIMIT") = kDriveStepLimit;
    m.attr("KINETIC_AT_PEAK_LIMIT") = kKineticAtPeakLimit;
    m.attr("RATE_PERIODS") = kRatePeriods;
    m.attr("PACED_RATE_PERIODS") = kPacedRatePeriods;
    m.def("drive_step", &driveStep, py::arg("strain_rate"), py::arg("dt"), py::arg("eps_p"),
          "the drive's displacement in one step over eps_p x the gauge length");
    m.def("brittle_warning", &brittleWarning, py::arg("material"), py::arg("L0"),
          "a warning ('' if none) when the bars of the mean G_f are perfectly brittle by construction");
    m.def("brittle_fracture_energy", &brittleFractureEnergy, py::arg("material"), py::arg("L0"), py::arg("diagonal"),
          "the G_f below which a bar (normal, or diagonal) is perfectly brittle: E A eps_p^2 L / (2 A_f) [N/m]");
    py::class_<LoadLossDetector>(m, "LoadLossDetector", "the load-loss test of Simulation.run, one record at a time")
        .def(py::init<double, double>(), py::arg("window"), py::arg("fraction"))
        .def("update", &LoadLossDetector::update, py::arg("time"), py::arg("stress"), py::arg("peak_stress"),
             py::arg("broken"));
    m.def(
        "nodes_joined",
        [](const Lattice& lat, const std::vector<std::uint8_t>& intact, const std::vector<std::int32_t>& a,
           const std::vector<std::int32_t>& b) { return nodesJoined(lat, intact, a, b); },
        py::arg("lattice"), py::arg("intact"), py::arg("a"), py::arg("b"),
        "True if a chain of intact bars (intact[bar] != 0) joins a node of a to a node of b: Simulation.run's separation test");
    m.def(
        "max_flow",
        [](std::int64_t nodes, const py::handle& n1, const py::handle& n2, const py::handle& capacity,
           const py::handle& sources, const py::handle& sinks) {
            using I = std::int64_t;
            return maxFlow(nodes, fromNumpy<I>(n1), fromNumpy<I>(n2), fromNumpy<I>(capacity), fromNumpy<I>(sources),
                           fromNumpy<I>(sinks));
        },
        py::arg("nodes"), py::arg("n1"), py::arg("n2"), py::arg("capacity"), py::arg("sources"), py::arg("sinks"),
        "the maximum flow from sources to sinks over the undirected edges {n1, n2} of integer capacity "
        "(pkg/ldem/MaxFlow.hpp): the cheapest cut's value (ldem.mincut)");
    // The bar laws' damage states (pkg/ldem/laws/BarLaw.hpp), for outputs and pictures.
    m.attr("UNDAMAGED") = int(DamageState::Undamaged);
    m.attr("DAMAGED") = int(DamageState::Damaged);
    m.attr("BROKEN") = int(DamageState::Broken);

    py::class_<Lattice>(m, "Lattice", "the cubic lattice with centre nodes: nodes, bars in rows, masses")
        .def("__repr__", [](const Lattice& l) {
            return "Lattice(" + std::to_string(l.nx) + " x " + std::to_string(l.ny) + " x " + std::to_string(l.nz) +
                   " modules of L0 = " + formatNumber(l.L0) + " m, " + std::to_string(l.numNodes()) + " nodes, " +
                   std::to_string(l.numBars()) + " bars)";
        })
        .def_readonly("nx", &Lattice::nx)
        .def_readonly("ny", &Lattice::ny)
        .def_readonly("nz", &Lattice::nz)
        .def_readonly("L0", &Lattice::L0)
        .def_readonly("k_offset", &Lattice::kOffset, "global module layer of this box's lowest (0 unless a slab)")
        .def_readonly("nz_total", &Lattice::nzTotal, "module layers of the whole lattice")
        .def_property_readonly("owned_bars", &Lattice::ownedBars,
                               "(first, end): the bars this rank owns (all of them unless a slab)")
        .def_property_readonly("is_slab", &Lattice::isSlab)
        .def_property_readonly("n_nodes", &Lattice::numNodes)
        .def_property_readonly("n_bars", &Lattice::numBars)
        .def_property_readonly("x0", [](const Lattice& l) { return toNumpy(nodePositions(l)[0]); })
        .def_property_readonly("y0", [](const Lattice& l) { return toNumpy(nodePositions(l)[1]); })
        .def_property_readonly("z0", [](const Lattice& l) { return toNumpy(nodePositions(l)[2]); })
        .def_property_readonly("mass", [](const Lattice& l) { return toNumpy(l.mass); })
        .def("bar_table", [](const Lattice& l) {  // every bar listed explicitly, as numpy arrays
            BarTable t = listBars(l);
            std::vector<std::uint8_t> kind(t.family.size());
            for (std::size_t b = 0; b < kind.size(); ++b) kind[b] = std::uint8_t(l.families[t.family[b]].kind);
            py::dict d;
            d["n1"] = toNumpy(t.n1), d["n2"] = toNumpy(t.n2), d["family"] = toNumpy(t.family);
            d["kind"] = toNumpy(kind);  // 0 edge, 1 centre-centre, 2 diagonal
            d["share"] = toNumpy(t.share), d["EA"] = toNumpy(t.EA), d["Af"] = toNumpy(t.Af), d["length"] = toNumpy(t.L);
            return d;
        });
    m.def("build_cubic_lattice", &buildCubicLattice, py::arg("nx"), py::arg("ny"), py::arg("nz"), py::arg("L0"),
          py::arg("material"));
    m.def("build_lattice", &buildLattice, py::arg("nx"), py::arg("ny"), py::arg("nz"), py::arg("L0"), py::arg("material"),
          py::arg("module_mask"),
          "the lattice of the present modules of an nx x ny x nz box: module_mask[i + nx (j + ny k)] != 0 "
          "(empty: all); nodes of no present module keep their ids with mass 0");
    m.def("lattice_frequencies",
          [](const Lattice& lat, const std::vector<std::uint8_t>& mask) {
              const Frequencies f = latticeFrequencies(lat, mask);
              return py::make_tuple(f.omega1, f.omegaMax);
          },
          py::arg("lattice"), py::arg("mask"),
          "(omega_1, omega_max) [rad/s] of the undamaged lattice with the DOFs of mask held (per node, bit d: DOF d)");
    m.def("expected_node_count", &expectedNodeCount);
    m.def("expected_bar_count", &expectedBarCount);
    m.def("memory_estimate", &memoryEstimate, py::arg("nx"), py::arg("ny"), py::arg("nz"),
          "bytes a run of an nx x ny x nz lattice takes (kBytesPerBar a bar, Lattice.hpp)");
    m.def("check_fits", [](int nx, int ny, int nz) {
              const auto [k0, k1] = worldSlab(nz);
              checkFits(nx, ny, nz, k0, k1);
          }, py::arg("nx"), py::arg("ny"), py::arg("nz"),
          "raises ValueError, with the estimate, unless this process's slab of the nx x ny x nz lattice fits it "
          "(the check every builder makes before it allocates)");
    m.def("memory_limit", [] {
              const MemoryLimit have = memoryLimit();
              return py::make_tuple(have.bytes, have.what);
          }, "(bytes, which) of the smallest room a lattice may take: the machine's available memory, the "
             "cgroup's limit less its usage, the address-space limit (ulimit -v) less the process's size");
    m.def("lattice_misfit", [](int nx, int ny, int nz, double bytes) {
              return latticeMisfit(nx, ny, nz, 0, nz, MemoryLimit{bytes, "this machine has"});
          }, py::arg("nx"), py::arg("ny"), py::arg("nz"), py::arg("bytes"),
          "why the whole nx x ny x nz lattice does not fit one process of `bytes` of memory ('' if it does)");

    // The laws' names, in registry order (laws/Registry.hpp): the choices of the `law` parameter.
    m.attr("bar_laws") = barLawNames();
    // The dynamic parts' registry (pkg/ldem/dynamics/Registry.hpp): each part's family, name, doc and parameters.
    {
        py::list parts;
        auto row = [&](const char* family, const char* name, const char* doc, bool choice,
                       std::vector<std::string> params) {
            py::dict d;
            d["family"] = family, d["name"] = name, d["doc"] = doc, d["choice"] = choice, d["parameters"] = params;
            parts.append(d);
        };
#define LDEM_PARAM_NAME(type, member, name, def, unit, domain, help) name,
#define LDEM_DRIVE_ROW(Type, LIST, X) row("drive", Type::name, Type::doc, Type::kChoice, {LIST(LDEM_PARAM_NAME)});
#define LDEM_STOP_ROW(Type, LIST, X) row("stop", Type::name, Type::doc, Type::kChoice, {LIST(LDEM_PARAM_NAME)});
#define LDEM_DAMPING_ROW(Type, LIST, X) row("damping", Type::name, Type::doc, true, {LIST(LDEM_PARAM_NAME)});
        LDEM_DRIVES(LDEM_DRIVE_ROW, _)
        LDEM_DAMPINGS(LDEM_DAMPING_ROW, _)
        LDEM_STOPS(LDEM_STOP_ROW, _)
#undef LDEM_PARAM_NAME
#undef LDEM_DRIVE_ROW
#undef LDEM_STOP_ROW
#undef LDEM_DAMPING_ROW
        m.attr("dynamic_parts") = parts;
    }
    // Every law's one-bar functions (pkg/ldem/laws/), for tests and for anyone who wants to plot them.
    forEachLawType([&](auto* law) {
        std::remove_pointer_t<decltype(law)>::singles([&](const char* name, const char* doc, auto f, auto... args) {
            m.def(name, f, doc, py::arg(args)...);
        });
    });
    m.def("nayfeh_delta", &nayfehDelta);
    m.def("nayfeh_phi", &nayfehPhi);
    m.def("weibull_from_mean_cv", [](double mean, double cv, double location) {
        const Weibull w = weibullFromMeanCV(mean, cv, location);
        return py::make_tuple(w.shape, w.scale);
    }, py::arg("mean"), py::arg("cv"), py::arg("location") = 0.0,
          "(shape, scale) of the Weibull of this mean, CV and location (lower bound)");
    m.def("max_threads", &maxThreads);
    m.def("default_thread_count", &defaultThreadCount, py::arg("bars"), py::arg("free_cores"), py::arg("processes") = 1,
          "the default thread count's rule (threads = 0) for a lattice of `bars` bars on `free_cores` free cores");
    m.def("allowed_cores", &allowedCores, "the cores this process may run on (affinity, cgroup quota)");
    m.def("idle_cores", &idleCores, py::arg("seconds") = 0.1, "of the allowed cores, those idle over `seconds`");

    py::class_<Simulation> sim(m, "Simulation",
                           "a specimen and its run: Simulation(CubeTestParams) for a cube test, or "
                           "Simulation(nx, ny, nz, L0, material, loading, run), or any specimen; run(observer) is "
                           "the time-step loop");
    sim.def("__repr__", [](const Simulation& s) {
            const Lattice& l = s.lattice();
            return "Simulation(" + std::to_string(l.nx) + " x " + std::to_string(l.ny) + " x " + std::to_string(l.nz) +
                   " modules, " + std::to_string(l.numBars()) + " bars, dt = " + formatNumber(s.dt()) + " s, step " +
                   std::to_string(s.stepCount()) + ")";
        })
        .def(py::init([](int nx, int ny, int nz, double L0, const Material& mat, const LoadingParams& load,
                         const RunParams& run) {
                 py::gil_scoped_release release;  // the modal analysis can take seconds
                 // Under mpirun, this rank's slab only (pkg/ldem/Slab.hpp).
                 return std::make_unique<Simulation>(cubeTestSpecimen(nx, ny, nz, L0, mat, load, {}, worldSlab(nz)),
                                                     mat, load, run);
             }),
             py::arg("nx"), py::arg("ny"), py::arg("nz"), py::arg("L0"), py::arg("material"), py::arg("loading"),
             py::arg("run"))
        .def(py::init([](const CubeTestParams& p) {
                 py::gil_scoped_release release;
                 return std::make_unique<Simulation>(cubeTestSpecimen(p), p.material, p.loading, p.run);
             }),
             py::arg("params"), "the cube test of params (ldem.CubeTest builds them)")
        .def(py::init([](int nx, int ny, int nz, double L0, const std::vector<std::uint8_t>& moduleMask,
                         const std::map<std::string, std::vector<std::int32_t>>& groups,
                         const std::vector<std::int32_t>& node, const std::vector<std::uint8_t>& dim,
                         const std::vector<double>& weight, const py::dict& measures, const Material& mat,
                         const LoadingParams& load, const RunParams& run) {
                 Measures ms;
                 ms.support = measures["support"].cast<std::string>();
                 ms.loaded = measures["loaded"].cast<std::string>();
                 ms.dim = measures["dim"].cast<int>();
                 ms.area = measures["area"].cast<double>();
                 ms.gaugeLength = measures["gauge_length"].cast<double>();
                 if (measures.contains("ligament")) ms.ligament = measures["ligament"].cast<double>();
                 ms.meanDriveWeight = measures["mean_drive_weight"].cast<double>();
                 if (measures.contains("probes"))
                     for (const auto& q : measures["probes"].cast<py::list>()) {
                         const auto t = q.cast<py::tuple>();
                         ms.probes.push_back({t[0].cast<std::string>(), t[1].cast<std::int32_t>(),
                                              t[2].cast<std::int32_t>(), t[3].cast<int>()});
                     }
                 if (measures.contains("control")) ms.control = measures["control"].cast<int>();
                 py::gil_scoped_release release;
                 // Under mpirun, this rank's slab only (pkg/ldem/Slab.hpp).
                 return std::make_unique<Simulation>(
                     specimenSlab(nx, ny, nz, L0, mat, moduleMask, groups, node, dim, weight, ms, worldSlab(nz)),
                     mat, load, run);
             }),
             py::arg("nx"), py::arg("ny"), py::arg("nz"), py::arg("L0"), py::arg("module_mask"), py::arg("groups"),
             py::arg("prescribed_node"), py::arg("prescribed_dim"), py::arg("prescribed_weight"), py::arg("measures"),
             py::arg("material"), py::arg("loading"), py::arg("run"),
             "any specimen: the nx x ny x nz lattice of the modules of module_mask (as build_lattice), named node "
             "groups, prescribed DOFs u[node][dim] = weight x U(t), and measures {support, loaded, dim, area, "
             "gauge_length, ligament (0: none), mean_drive_weight, probes: [(name, a, b, dim)], control: index of "
             "the probe held to opening_rate, or -1}, node ids of the whole lattice (ldem.specimen builds them from "
             "a file)")
        .def(
            "run",
            [](Simulation& s, py::object callback) {
                std::function<bool(const CurvePoint&)> observer;
                if (!callback.is_none())
                    observer = [&callback](const CurvePoint& p) {
                        py::gil_scoped_acquire gil;
                        py::object r = callback(p);
                        return r.is_none() || r.cast<bool>();
                    };
                py::gil_scoped_release release;
                return s.run(observer);
            },
            py::arg("callback") = py::none(),
            "Runs the time-step loop; callback(point) is called at every record and may return False to stop.")
        .def("step", &Simulation::step)
        .def("force_time_step", &Simulation::forceTimeStep,
             "Sets dt WITHOUT the stability check (for tests of the instability detector).")
        .def("compute_forces", &Simulation::computeForces)
        .def("advance", &Simulation::advance)
        .def("measure", &Simulation::measure)
        .def_property_readonly("lattice", &Simulation::lattice, py::return_value_policy::reference_internal)
        .def_property_readonly("dt", &Simulation::dt)
        .def_property_readonly("strain_rate", [](const Simulation& s) { return s.drive().strainRate; },
                               "the strain rate driven [1/s]: strain_rate, or rule (c)'s from rate_periods")
        .def_property_readonly("dt_limit", &Simulation::stableTimeStepLimit)
        .def_property_readonly("omega1", [](const Simulation& s) { return s.frequencies().omega1; })
        .def_property_readonly("omega_max", [](const Simulation& s) { return s.frequencies().omegaMax; })
        .def_property_readonly("omega_d", [](const Simulation& s) { return s.frequencies().omegaDrive; },
                               "the drive's own frequency [rad/s]: the Rayleigh quotient of its elastic field, "
                               "what times the smooth start and rule (c)")
        .def_property_readonly("drive_cg_iterations",
                               [](const Simulation& s) { return s.frequencies().driveIterations; })
        .def_property_readonly("lanczos_iterations", [](const Simulation& s) { return s.frequencies().iterations; })
        .def_property_readonly("damping_coefficient", &Simulation::dampingCoefficient)
        .def_property_readonly("part_names", &Simulation::partNames,
                               "the run's dynamic parts by role and name, as in a checkpoint (drive_adaptive, ...)")
        .def("faces_joined", &Simulation::facesJoined, "some chain of intact bars joins the upper and lower faces")
        .def_property_readonly("ramp_time", &Simulation::rampTime)
        .def_property_readonly("split_window", &Simulation::splitWindow)
        .def_property_readonly("loading", &Simulation::loading)
        .def("drive_displacement", [](const Simulation& s, double t) { return s.drive().displacement(t); },
             py::arg("t"), "U(t): the prescribed displacement of the most-pulled upper node [m]")
        .def("prescribed_dofs",
             [](const Simulation& s) {  // u[node][dim] = weight * U(t)
                 const Prescribed& c = s.prescribed();
                 py::dict d;
                 d["node"] = toNumpy(c.node), d["dim"] = toNumpy(c.dim), d["weight"] = toNumpy(c.weight);
                 return d;
             })
        .def("checkpoint", [](const Simulation& s) { return checkpointDict(s.checkpoint()); },
             "the state at the record being observed, as named arrays (call it from run()'s observer)")
        .def("restore", [](Simulation& s, const py::dict& d) { s.restore(checkpointOf(s, d)); }, py::arg("state"),
             "set back to a checkpoint: the next run() continues that run bit for bit")
        .def_property_readonly("resumable", &Simulation::resumable,
                               "restored (or stopped within its observer): run() continues it")
        .def_property_readonly("clamped_bars", &Simulation::clampedBars)
        .def_property_readonly("total_bars", &Simulation::totalBars, "bars of the whole lattice (all MPI ranks)")
        .def_property_readonly("total_nodes", &Simulation::totalNodes, "nodes of the whole lattice (all MPI ranks)")
        .def_property_readonly("steps", &Simulation::stepCount)
        .def_property_readonly("record_every", &Simulation::recordEvery)
        .def_property_readonly("threads", &Simulation::threads,
                               "the OpenMP threads of the run: threads if set, else OMP_NUM_THREADS, else as many as "
                               "the lattice can use and the machine has free (Parallel.hpp, threadsFor)")
        .def_property_readonly("min_fracture_energy", &Simulation::minFractureEnergy,
                               "U_min = E[G_f] x the ligament's area [J] (0: the specimen declares no ligament)")
        .def_property_readonly("summary_so_far", &Simulation::summarySoFar,
                               "the run's summary as of its last record (an interrupted run's peak and events)")
        .def_property_readonly("area", [](const Simulation& s) { return s.measures().area; },
                               "area the reactions are divided by [m^2]")
        .def_property_readonly("gauge_length", [](const Simulation& s) { return s.measures().gaugeLength; },
                               "length the drive's displacement is divided by [m] (the cube's height)")
        .def_property_readonly("measures",
                               [](const Simulation& s) {
                                   const Measures& m = s.measures();
                                   py::dict d;
                                   d["support"] = m.support, d["loaded"] = m.loaded, d["dim"] = m.dim;
                                   d["area"] = m.area, d["gauge_length"] = m.gaugeLength;
                                   d["ligament"] = m.ligament;
                                   d["mean_drive_weight"] = m.meanDriveWeight;
                                   d["sense"] = m.sense();  // +1 pulled, -1 pushed (Measures::sense)
                                   py::list probes;
                                   for (const Probe& q : m.probes) probes.append(py::make_tuple(q.name, q.a, q.b, q.dim));
                                   d["probes"] = probes;
                                   d["control"] = m.control;
                                   return d;
                               })
        .def_property_readonly("group_names",
                               [](const Simulation& s) {
                                   std::vector<std::string> names;
                                   for (const auto& g : s.groups()) names.push_back(g.first);
                                   return names;
                               })
        .def(
            "group", [](const Simulation& s, const std::string& name) { return toNumpy(s.group(name)); },
            py::arg("name"), "the nodes of a named group (the cube: 'bottom', 'top')")
        .def_property_readonly("fracture_energy_field", [](const Simulation& s) { return toNumpy(s.fractureEnergyField()); })
        .def_property_readonly("rupture_energy", [](const Simulation& s) { return toNumpy(s.ruptureEnergies()); },
                               "energy each bar dissipates when it breaks [J] (A_f G_f; 1/2 L EA eps_p^2 if clamped)")
        .def_property_readonly("bytes_sent", [](const Simulation&) { return Comm::world().bytesSent(); },
                               "bytes this rank has sent to its neighbours (halo exchanges)")
        .def_property_readonly("damage_state", [](const Simulation& s) { return toNumpy(s.damageStates()); },
                               "per bar: UNDAMAGED, DAMAGED or BROKEN (by the bar law)")
        .def_property_readonly("bar_force", [](const Simulation& s) { return toNumpy(s.barForces()); },
                               "axial force of every bar [N], tension positive")
        .def_property_readonly("bar_strain", [](const Simulation& s) { return toNumpy(barStrains(s.lattice(), s.displacements())); })
        .def_property_readonly("displacement", [](const Simulation& s) {
            const Field3& u = s.displacements();
            py::array_t<double> a({py::ssize_t(u.x.size()), py::ssize_t(3)});
            auto r = a.mutable_unchecked<2>();
            for (py::ssize_t i = 0; i < py::ssize_t(u.x.size()); ++i) r(i, 0) = u.x[i], r(i, 1) = u.y[i], r(i, 2) = u.z[i];
            return a;
        });
    // The law's per-bar state through its interface (laws/BarLaw.hpp: arrays()), whatever the law.
    sim.def("law_state", [](const Simulation& s) {
        py::dict d;
        std::visit([&](const auto& law) {
            for (const auto& [name, values] : law.arrays()) d[name.c_str()] = toNumpy(*values);
        }, s.law());
        return d;
    }, "the bar law's per-bar state, by name: numpy arrays (every law: kappa, the damage, and eps_r; its own)");
    // The bar laws' state by name: per-bar arrays (the Hillerborg law's kappa, eps_r) and constants (eps_p).
    forEachLawType([&](auto* law) {
        const std::remove_pointer_t<decltype(law)> names{};
        for (const auto& a : names.arrays())
            sim.def_property_readonly(a.first.c_str(), [name = a.first](const Simulation& s) {
                return toNumpy(s.barArray(name));
            });
        for (const auto& c : names.constants())
            sim.def_property_readonly(c.first.c_str(), [name = c.first](const Simulation& s) {
                return s.lawConstant(name);
            });
    });
}
