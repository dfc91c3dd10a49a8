// The registry of the dynamic parts (Part.hpp): every drive, damping and stop
// rule, one line each, P(Type, its parameter list, X). A new part is its header
// in this folder and its line here; its parameters join its group's
// (Loading.hpp, RunParams.hpp), a drive's or a stop rule's name the choices of
// tail_drive or stop_at (driveNames, stopNames), a damping's those of dampings
// (dampingNames: a run applies the ones it names), and Parts.hpp builds it by
// name. The checks below run at compile time.
#pragma once
#include <functional>
#include <array>
#include <cstddef>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "ldem/dynamics/AdaptiveDrive.hpp"
#include "ldem/dynamics/BarDashpots.hpp"
#include "ldem/dynamics/ConstantRateDrive.hpp"
#include "ldem/dynamics/ConstantVelocityDrive.hpp"
#include "ldem/dynamics/ConvergedStop.hpp"
#include "ldem/dynamics/FinalStrainStop.hpp"
#include "ldem/dynamics/LoadLoss.hpp"
#include "ldem/dynamics/LoadLossStop.hpp"
#include "ldem/dynamics/MassDamping.hpp"
#include "ldem/dynamics/PastPeakStop.hpp"
#include "ldem/dynamics/QuasiStatic.hpp"
#include "ldem/dynamics/SeparationStop.hpp"
#include "ldem/dynamics/ServoDrive.hpp"

#define LDEM_DRIVES(P, X)                                      \
    P(ConstantRateDrive, LDEM_NO_PARAMETERS, X)                \
    P(AdaptiveTailDrive, LDEM_ADAPTIVE_DRIVE_PARAMETERS, X)    \
    P(ServoDrive, LDEM_SERVO_PARAMETERS, X)                    \
    P(ConstantVelocityDrive, LDEM_CONSTANT_VELOCITY_PARAMETERS, X)
#define LDEM_DAMPINGS(P, X)                                    \
    P(MassDamping, LDEM_MASS_DAMPING_PARAMETERS, X)            \
    P(BarDashpots, LDEM_BAR_DASHPOT_PARAMETERS, X)
#define LDEM_STOPS(P, X)                                       \
    P(SeparationStop, LDEM_NO_PARAMETERS, X)                   \
    P(LoadLossStop, LDEM_LOAD_LOSS_STOP_PARAMETERS, X)         \
    P(ConvergedStop, LDEM_CONVERGED_STOP_PARAMETERS, X)        \
    P(PastPeakStop, LDEM_PAST_PEAK_STOP_PARAMETERS, X)         \
    P(FinalStrainStop, LDEM_FINAL_STRAIN_STOP_PARAMETERS, X)

// A family's parameter lists, spliced into its group's list (LDEM_DRIVES(LDEM_PART_LIST, X)).
#define LDEM_PART_LIST(Type, LIST, X) LIST(X)
#define LDEM_PART_TYPE(Type, LIST, X) , Type

namespace ldem {

template <class Void, class... Part>
using VariantOf = std::variant<Part...>;
template <class Void, class... Part>
using TupleOf = std::tuple<Part...>;
using Drives = VariantOf<void LDEM_DRIVES(LDEM_PART_TYPE, _)>;
using StopRules = VariantOf<void LDEM_STOPS(LDEM_PART_TYPE, _)>;
using Dampings = TupleOf<void LDEM_DAMPINGS(LDEM_PART_TYPE, _)>;  // those named in dampings applied, in this order

// f(static_cast<Part*>(nullptr)) for every type of a variant or a tuple, in registry order.
template <template <class...> class List, class... Part, class F>
void forEachPartType(const List<Part...>*, F f) {
    (f(static_cast<Part*>(nullptr)), ...);
}

// What Parts.hpp and Simulation ask of every drive, every stop rule and every damping, checked on each.
template <class Part>
constexpr bool isPart() {
    static_assert(std::is_same_v<decltype(Part::name), const char* const>, "a part's name");
    static_assert(std::is_default_constructible_v<typename Part::Params>, "a part's Params, from its list");
    static_assert(std::is_same_v<decltype(std::declval<const Part&>().state()), std::vector<double>>, "state()");
    static_assert(std::is_void_v<decltype(std::declval<Part&>().setState(std::vector<double>{}))>, "setState()");
    return true;
}
template <class D>
constexpr bool isDrive() {
    static_assert(std::is_same_v<decltype(D::doc), const char* const>, "a drive's doc: tail_drive's help");
    static_assert(std::is_same_v<decltype(D::kChoice), const bool>, "kChoice: a choice of tail_drive");
    static_assert(std::is_constructible_v<D, const typename D::Params&, const DriveSetup&>, "D(Params, DriveSetup)");
    static_assert(std::is_same_v<decltype(D::select(typename D::Params{}, DriveSetup{}, true)), const char*>,
                  "select(Params, DriveSetup, chosen): the drive to build");
    static_assert(std::is_void_v<decltype(std::declval<D&>().setUp(RunSetup{}))>, "setUp(RunSetup)");
    static_assert(std::is_same_v<decltype(std::declval<const D&>().now(0.0, 0.0)), double>, "now(t, dt)");
    static_assert(std::is_same_v<decltype(std::declval<const D&>().before(0.0, 0.0)), double>, "before(t, dt)");
    static_assert(std::is_same_v<decltype(std::declval<D&>().next(DriveStep{})), double>, "next(DriveStep)");
    static_assert(std::is_void_v<decltype(std::declval<D&>().record(std::declval<const DriveRecord&>()))>, "record");
    static_assert(std::is_same_v<decltype(std::declval<const D&>().program()), const Drive&>, "program()");
    return isPart<D>();
}
template <class S>
constexpr bool isStop() {
    static_assert(std::is_same_v<decltype(S::doc), const char* const>, "a stop rule's doc: stop_at's help");
    static_assert(std::is_same_v<decltype(S::kChoice), const bool>, "kChoice: a choice of stop_at");
    static_assert(std::is_same_v<decltype(S::kAlways), const bool>, "kAlways: in every run");
    static_assert(std::is_constructible_v<S, const typename S::Params&>, "S(Params)");
    static_assert(std::is_void_v<decltype(std::declval<const S&>().setUp(RunSetup{}))>, "setUp(RunSetup) const");
    static_assert(std::is_void_v<decltype(std::declval<S&>().record(std::declval<StopRecord&>()))>, "record");
    static_assert(std::is_same_v<decltype(std::declval<const S&>().reason(CurvePoint{}, RunSummary{})), const char*>,
                  "reason(point, summary): the stop's reason, or nullptr");
    return isPart<S>();
}
template <class D>
constexpr bool isDamping() {
    static_assert(std::is_same_v<decltype(D::doc), const char* const>, "a damping's doc: dampings' help");
    static_assert(std::string_view(D::name) != "none", "none is no damping (dampings)");
    static_assert(std::is_constructible_v<D, const typename D::Params&, const DampingSetup&>, "D(Params, DampingSetup)");
    static_assert(std::is_same_v<decltype(std::declval<const D&>().stepFactor()), double>, "stepFactor()");
    static_assert(std::is_same_v<decltype(std::declval<D&>().nodeUpdate(CentralDifference(0, 0))), CentralDifference>,
                  "nodeUpdate(cd)");
    static_assert(std::is_same_v<decltype(std::declval<D&>().barPass(Field3())), DashpotPass>, "barPass(v)");
    static_assert(std::is_same_v<decltype(std::declval<const D&>().deferred()), bool>, "deferred()");
    static_assert(std::is_same_v<decltype(std::declval<const D&>().waits(0)), bool>, "waits(m)");
    static_assert(std::is_void_v<decltype(std::declval<D&>().followLayer(
                      0, std::declval<const Lattice&>(), std::declval<const std::vector<std::uint8_t>&>(),
                      std::declval<const Field3&>(), std::declval<const Field3&>(), std::declval<Field3&>(),
                      std::declval<const std::function<void(int)>&>()))>,
                  "followLayer(m, lat, mask, u, v, f, move)");
    static_assert(std::is_void_v<decltype(std::declval<D&>().afterForces(
                      std::declval<const Lattice&>(), std::declval<const std::vector<std::uint8_t>&>(),
                      std::declval<const Field3&>(), std::declval<const Field3&>(), std::declval<Field3&>(),
                      std::declval<const std::function<void(int)>&>(), false))>,
                  "afterForces(lat, mask, u, v, f, moveWaiting, followed)");
    static_assert(std::is_same_v<decltype(std::declval<const D&>().stepWork(0)), double>, "stepWork(m)");
    static_assert(std::is_same_v<decltype(std::declval<const D&>().closingWork(0)), double>, "closingWork(m)");
    static_assert(std::is_same_v<decltype(std::declval<const D&>().coefficient()), double>, "coefficient(): D_f");
    static_assert(std::is_same_v<decltype(std::declval<const D&>().lag()), double>, "lag(): the relative tail's");
    static_assert(std::is_void_v<decltype(std::declval<D&>().record(std::declval<const DampingRecord&>()))>, "record");
    return isPart<D>();
}
template <template <class...> class List, class... Part>
constexpr bool namesAreUnique(const List<Part...>*) {
    const std::array<std::string_view, sizeof...(Part)> names{Part::name...};
    for (std::size_t i = 0; i < names.size(); ++i)
        for (std::size_t j = 0; j < i; ++j)
            if (names[i] == names[j] || names[i].empty()) return false;
    return true;
}
template <class... D>
constexpr bool allDrives(const std::variant<D...>*) { return (isDrive<D>() && ...); }
template <class... S>
constexpr bool allStops(const std::variant<S...>*) { return (isStop<S>() && ...); }
template <class... D>
constexpr bool allDampings(const std::tuple<D...>*) { return (isDamping<D>() && ...); }
static_assert(allDrives(static_cast<const Drives*>(nullptr)) && namesAreUnique(static_cast<const Drives*>(nullptr)),
              "two drives share a name (or one has none)");
static_assert(allStops(static_cast<const StopRules*>(nullptr)) &&
              namesAreUnique(static_cast<const StopRules*>(nullptr)), "two stop rules share a name (or one has none)");
static_assert(allDampings(static_cast<const Dampings*>(nullptr)) &&
              namesAreUnique(static_cast<const Dampings*>(nullptr)), "two dampings share a name (or one has none)");
static_assert(std::tuple_size_v<Dampings> <= 8, "DampingSet holds a bit per damping: 8 at most");

}  // namespace ldem
