// What every law of the family here shares (the interface: laws/BarLaw.hpp):
// elastic up to eps_p, then a softening envelope F_env(kappa) that reaches
// zero force at eps_r; damage kappa = the largest strain reached; below kappa
// the bar follows the secant to the origin, F = EA eps s(kappa),
// s(kappa) = F_env(kappa) / (EA kappa); compression is elastic, also after
// rupture (crack closure). Written once here: the per-bar state, the
// realisation of the per-bar parameters from the material and the G_f field,
// the row functor of the force loop, and the accessors.
//
// A law of this family is SecantLaw<Shape>, its Shape a struct holding its
// envelope (laws/Hillerborg.hpp is one):
//   static constexpr const char* name;                   the `law` parameter's choice
//   struct Params;  static Params params(const Material&);  its constants (a list of
//   static constants(const Params&)                      Parameters.hpp, LDEM_PART_PARAMS), by name;
//                                                        NoParams below: none
//   static constexpr std::array<const char*, N> kBarParams;  per-bar parameters besides eps_r
//   using Bar = std::array<double, N>;
//   static Realised<N> realise(Af, Gf, EA, epsP, L, params)   a bar's eps_r and Bar (Realised below)
//   static double secantRatio(kappa, epsP, epsR, bar, params)  s(kappa): 1 up to eps_p, 0 from eps_r
//   static double dissipated(kappa, EA, epsP, epsR, bar, params, L)  the energy dissipated at damage kappa [J]
//   static void singles(Def def)                         its one-bar functions for Python
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "ldem/Interrupt.hpp"
#include "ldem/Lattice.hpp"
#include "ldem/Material.hpp"
#include "ldem/laws/BarLaw.hpp"

namespace ldem {

// A bar's parameters realised from its G_f: its rupture strain, the shape's others.
template <std::size_t N>
struct Realised {
    double epsR;
    std::array<double, N> bar;
    bool clamped;  // the envelope would have snapped back: made (more) brittle
};

// A shape without constants of its own.
struct NoParams {
    struct Params {};
    static Params params(const Material&) { return {}; }
    static std::vector<std::pair<std::string, double>> constants(const Params&) { return {}; }
};

// The name and value of every member of a constants' list (Parameters.hpp), for constants().
#define LDEM_NAMED_MEMBER(type, member, name, def, unit, domain, help) {name, double(p.member)},

template <class Shape>
class SecantLaw {
public:
    static constexpr const char* name = Shape::name;
    static constexpr std::size_t N = Shape::kBarParams.size();
    using Params = typename Shape::Params;
    using Bar = std::array<double, N>;

    // Per-bar state, in double precision: the damaged regime is chaotic, and
    // rounding kappa or eps_r to float moved the peak of the 0.24 m cube by
    // 3e-4 (measured), far above rounding.
    double epsP = 0;            // critical strain (same for all bars)
    Params params{};            // the shape's constants (same for all bars)
    std::array<std::vector<double>, N> bar;  // the shape's per-bar parameters (kBarParams)
    std::vector<double> epsR;   // strain of rupture of each bar
    // Damage: the largest strain reached, recorded once it passes eps_p (the
    // law does not depend on it below eps_p, so elastic bars never write it).
    std::vector<double> kappa;
    // Per bar row: its RowPath (laws/BarLaw.hpp), elastic until some bar of the row passes eps_p.
    std::vector<std::uint8_t> softening;

    SecantLaw() = default;
    // Undamaged bars of lat with the given rupture strains (a shape without per-bar parameters).
    SecantLaw(const Lattice& lat, double epsP_, std::vector<double> epsR_)
        : epsP(epsP_), epsR(std::move(epsR_)), kappa(lat.numBars(), 0.0), softening(lat.barRows.size(), 0) {}
    // Undamaged bars of lat of material m, the parameters of each from its G_f
    // (surface edges carry their share of both EA and A_f).
    SecantLaw(const Lattice& lat, const Material& m, const std::vector<double>& Gf)
        : SecantLaw(lat, m.epsP, std::vector<double>(lat.numBars())) {
        params = Shape::params(m);
        for (auto& values : bar) values.resize(epsR.size());
        const auto owned = lat.ownedBars();
        InterruptCheck heard;  // one pass over every bar: 0.15 s at 72^3 modules beside other work
        for (const BarRow& row : lat.barRows) {
            heard();
            const BarFamily& fam = lat.families[row.family];
            for (int p = 0; p < row.count; ++p) {
                const std::int64_t b = row.first + p;
                const double share = row.shareAt(p);
                const Realised<N> r = Shape::realise(fam.Af * share, Gf[b], fam.EA * share, epsP, fam.L, params);
                epsR[b] = r.epsR;
                for (std::size_t i = 0; i < N; ++i) bar[i][b] = r.bar[i];
                clamped_ += r.clamped && b >= owned.first && b < owned.second;
            }
        }
    }

    // The row functor (laws/BarLaw.hpp): elastic while eps <= eps_p (a row that
    // never left the elastic path has kappa = 0 throughout: the fast path needs no state).
    struct Rows {
        static constexpr bool kElasticOnly = false;  // (InternalForces.hpp: barLayer)
        double* kappa;
        const double* epsR;
        std::array<const double*, N> bar;
        double epsP, xP;  // xP: the stretch x of eps_p (laws/BarLaw.hpp)
        Params params;
        std::uint8_t* softeningRow;

        Rows forRow(std::int32_t r, std::int64_t first) const {
            Rows row = *this;
            row.kappa += first, row.epsR += first, row.softeningRow += r;
            for (auto& values : row.bar) values += first;
            return row;
        }
        std::uint8_t path() const { return *softeningRow; }
        void setPath(std::uint8_t path) const { *softeningRow = path; }

        double elastic(std::int64_t, const BarFamily& fam, double EA, double dux, double duy, double duz, double& gx,
                       double& gy, double& gz) const {
            return elasticBarForce(fam, EA, xP, dux, duy, duz, gx, gy, gz);
        }
        template <class Stretch>
        double operator()(std::int64_t p, double EA, const Stretch& s, double& gx, double& gy, double& gz) const {
            const double eps = s.strain();
            const double k = updateDamage(kappa[p], eps);
            kappa[p] = k > epsP ? k : kappa[p];
            const double r = forceRatio(eps, k, epsP, epsR[p], barAt(bar, p), params);
            const double Fl = s.elasticForcePerLength(EA) * r;
            gx = Fl * s.dx, gy = Fl * s.dy, gz = Fl * s.dz;
            return dashpotRatio(k, epsP, eps);
        }
    };
    Rows rows() {
        std::array<const double*, N> columns;
        for (std::size_t i = 0; i < N; ++i) columns[i] = bar[i].data();
        return {kappa.data(), epsR.data(), columns, epsP, stretchOfStrain(epsP), params, softening.data()};
    }

    // Bar b alone, at strain eps, with the damage of the last force evaluation [N].
    double force(std::int64_t b, double EA, double eps) const { return forceAt(b, EA, eps, kappa[b]); }
    // Energies and damage state of bar b at strain eps. kappa is the damage
    // reached at the last force evaluation; the bar can only have gone further
    // since, so take the larger. Stored: 1/2 F (l - L).
    double stored(std::int64_t b, double EA, double L, double eps) const {
        return 0.5 * forceAt(b, EA, eps, updateDamage(kappa[b], eps)) * eps * L;
    }
    double dissipated(std::int64_t b, double EA, double L, double eps) const {
        return Shape::dissipated(updateDamage(kappa[b], eps), EA, epsP, epsR[b], barAt(bar, b), params, L);
    }
    // What it dissipates at any damage beyond eps_r: A_f G_f, or 1/2 L EA eps_p^2 if clamped to perfectly brittle.
    double ruptureEnergy(std::int64_t b, double EA, double L) const {
        const double past = std::nextafter(epsR[b], std::numeric_limits<double>::infinity());
        return Shape::dissipated(past, EA, epsP, epsR[b], barAt(bar, b), params, L);
    }
    DamageState damage(std::int64_t b, double eps = 0) const {
        return damageState(updateDamage(kappa[b], eps), epsP, epsR[b]);
    }
    // A broken bar (kappa >= eps_r) carries no tension, ever again.
    bool intact(std::int64_t b) const { return kappa[b] < epsR[b]; }
    // Owned bars whose envelope would have snapped back.
    std::int64_t clampedOwnedBars() const { return clamped_; }

    // The state a checkpoint keeps (its keys in checkpoint.npz): kappa, the shape's, eps_r; and the constants.
    std::vector<std::pair<std::string, const std::vector<double>*>> arrays() const { return arraysOf(*this); }
    std::vector<std::pair<std::string, std::vector<double>*>> arrays() { return arraysOf(*this); }
    std::vector<std::uint8_t>& softeningRows() { return softening; }
    const std::vector<std::uint8_t>& softeningRows() const { return softening; }
    std::vector<std::pair<std::string, double>> constants() const {
        std::vector<std::pair<std::string, double>> c{{"eps_p", epsP}};
        for (auto& named : Shape::constants(params)) c.push_back(named);
        return c;
    }

    template <class Def>
    static void singles(Def def) {
        Shape::singles(def);
    }

private:
    // kappa = max over history of eps; by value (std::max of kappa[b] would select an address,
    // and the energy loop (InternalForces.cpp) would lose its fused multiply-adds: tests/golden).
    static double updateDamage(double kappa, double eps) { return std::max(kappa, eps); }
    template <class Self>
    static auto arraysOf(Self& self) {
        std::vector<std::pair<std::string, decltype(&self.kappa)>> a{{"kappa", &self.kappa}};
        for (std::size_t i = 0; i < N; ++i) a.emplace_back(Shape::kBarParams[i], &self.bar[i]);
        a.emplace_back("eps_r", &self.epsR);
        return a;
    }
    // Bar b's shape parameters from their columns (the law's vectors, or a row's pointers).
    template <class Columns>
    static Bar barAt(const Columns& columns, std::int64_t b) {
        Bar v;
        for (std::size_t i = 0; i < N; ++i) v[i] = columns[i][b];
        return v;
    }
    // F / (EA eps) at strain eps with damage kappa >= eps: s(kappa) in tension, 1 in compression.
    static double forceRatio(double eps, double k, double epsP, double epsR, Bar v, const Params& c) {
        return eps > 0.0 ? Shape::secantRatio(k, epsP, epsR, v, c) : 1.0;
    }
    double forceAt(std::int64_t b, double EA, double eps, double k) const {
        return EA * eps * forceRatio(eps, k, epsP, epsR[b], barAt(bar, b), params);
    }

    std::int64_t clamped_ = 0;
};

}  // namespace ldem
