// The constitutive law of one bar: Hillerborg's triangle (LDEM_SPEC section 3),
// whole: its pure functions, the per-bar state, the row functor of the force
// loop with its elastic fast path, the realisation of the limit strains from
// the random G_f, and its energies (the interface: laws/BarLaw.hpp).
//
//        F
//   EA eps_p |    /\            tension: elastic up to eps_p, linear softening
//            |   /  \           to zero force at eps_r; damage kappa = largest
//            |  /    \          strain reached; below kappa the bar follows the
//            | /      \         secant to the origin; compression is elastic,
//   ---------+/--------\---eps  also after rupture (crack closure).
//           /|  eps_p  eps_r
//
// Everything in namespace hillerborg is a pure function of (eps, kappa) and the
// bar's constants, so the hot loop, the energy bookkeeping and the tests share
// one definition.
#pragma once
#include <algorithm>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "ldem/Lattice.hpp"
#include "ldem/Material.hpp"
#include "ldem/laws/BarLaw.hpp"

namespace ldem {

namespace hillerborg {

struct LimitStrain {
    double epsR;   // limit strain actually used
    bool clamped;  // true if eps_r < eps_p had to be raised to eps_p (snap-back)
};

// Triangle area = U_elem = A_f G_f:  1/2 EA eps_p eps_r L = A_f G_f
//   =>  eps_r = 2 A_f G_f / (EA eps_p L).
// eps_r < eps_p would be a snap-back: clamp to a perfectly brittle bar.
inline LimitStrain limitStrain(double Af, double Gf, double EA, double epsP, double L) {
    const double epsR = 2.0 * Af * Gf / (EA * epsP * L);
    return epsR < epsP ? LimitStrain{epsP, true} : LimitStrain{epsR, false};
}

// Secant stiffness ratio s(kappa) = F_envelope(kappa) / (EA kappa), in [0, 1]:
//   1 for kappa <= eps_p,  eps_p (eps_r - kappa) / (kappa (eps_r - eps_p)) on the
//   softening branch,  0 for kappa >= eps_r.
// Written as selects, without branches, so that the bar loop vectorizes; a
// clamped bar (eps_r = eps_p) past eps_p gives -inf, hence 0.
inline double secantRatio(double kappa, double epsP, double epsR) {
    const double r = epsP * (epsR - kappa) / (kappa * (epsR - epsP));
    return kappa <= epsP ? 1.0 : (r > 0.0 ? r : 0.0);
}

// F / (EA eps) at strain eps with damage kappa >= eps (call updateDamage
// first): the secant ratio s(kappa) in tension, 1 in compression.
inline double forceRatio(double eps, double kappa, double epsP, double epsR) {
    return eps > 0.0 ? secantRatio(kappa, epsP, epsR) : 1.0;
}

// Axial force (tension positive) at strain eps with damage kappa >= eps
// (call updateDamage first): F = EA eps s(kappa) in tension, EA eps in compression.
inline double axialForce(double eps, double kappa, double EA, double epsP, double epsR) {
    return EA * eps * forceRatio(eps, kappa, epsP, epsR);
}

// kappa = max over history of eps (never negative).
inline double updateDamage(double kappa, double eps) { return std::max(kappa, eps); }

// Elastic energy stored at strain eps on the secant of kappa: 1/2 F (l - L).
inline double storedEnergy(double eps, double kappa, double EA, double epsP, double epsR, double L) {
    return 0.5 * axialForce(eps, kappa, EA, epsP, epsR) * eps * L;
}

// Energy dissipated at damage kappa: work along the envelope up to kappa minus
// the energy stored on the secant at kappa, i.e. the area of the triangle
// (0,0)-(eps_p, sigma_p)-(kappa, sigma(kappa)):
//   D = 1/2 L EA eps_p eps_r (kappa - eps_p) / (eps_r - eps_p),   eps_p < kappa < eps_r
//   D = 1/2 L EA eps_p eps_r = A_f G_f,                         kappa >= eps_r
// A clamped bar (eps_r = eps_p) loses its whole 1/2 L EA eps_p^2 at once.
inline double triangleEnergy(double EA, double epsP, double epsR, double L) { return 0.5 * L * EA * epsP * epsR; }
inline double dissipatedEnergy(double kappa, double EA, double epsP, double epsR, double L) {
    if (kappa <= epsP) return 0.0;
    const double full = triangleEnergy(EA, epsP, epsR, L);
    if (kappa >= epsR) return full;
    return full * (kappa - epsP) / (epsR - epsP);
}

}  // namespace hillerborg

class HillerborgLaw {
public:
    static constexpr const char* name = "hillerborg";

    // Per-bar state. Kept in double precision: the damaged regime is chaotic,
    // and rounding kappa or eps_r to float moved the peak of the 0.24 m cube by
    // 3e-4 (measured), far above rounding.
    double epsP = 0;            // critical strain (same for all bars)
    std::vector<double> epsR;   // limit strain of each bar
    // Damage: the largest strain reached, recorded once it passes eps_p (the
    // law does not depend on it below eps_p, so elastic bars never write it).
    std::vector<double> kappa;
    // Per bar row: its RowPath (laws/BarLaw.hpp), elastic until some bar of the row passes eps_p.
    std::vector<std::uint8_t> softening;

    HillerborgLaw() = default;
    // Undamaged bars of lat with the given limit strains.
    HillerborgLaw(const Lattice& lat, double epsP_, std::vector<double> epsR_)
        : epsP(epsP_), epsR(std::move(epsR_)), kappa(lat.numBars(), 0.0), softening(lat.barRows.size(), 0) {}
    // Undamaged bars of lat of material m, the limit strain of each from its G_f
    // (surface edges carry their share of both EA and A_f).
    HillerborgLaw(const Lattice& lat, const Material& m, const std::vector<double>& Gf)
        : HillerborgLaw(lat, m.epsP, std::vector<double>(lat.numBars())) {
        const auto owned = lat.ownedBars();
        for (const BarRow& row : lat.barRows) {
            const BarFamily& fam = lat.families[row.family];
            for (int p = 0; p < row.count; ++p) {
                const std::int64_t b = row.first + p;
                const double share = row.shareAt(p);
                const hillerborg::LimitStrain ls = hillerborg::limitStrain(fam.Af * share, Gf[b], fam.EA * share, m.epsP, fam.L);
                epsR[b] = ls.epsR;
                clamped_ += ls.clamped && b >= owned.first && b < owned.second;
            }
        }
    }

    // The row functor (laws/BarLaw.hpp): elastic while eps <= eps_p (a row that
    // never left the elastic path has kappa = 0 throughout: the fast path needs no state).
    struct Rows {
        static constexpr bool kElasticOnly = false;  // (InternalForces.hpp: barLayer)
        double* kappa;
        const double* epsR;
        double epsP, xP;  // xP: the stretch x of eps_p (laws/BarLaw.hpp)
        std::uint8_t* softeningRow;

        Rows forRow(std::int32_t r, std::int64_t first) const {
            Rows row = *this;
            row.kappa += first, row.epsR += first, row.softeningRow += r;
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
            const double k = hillerborg::updateDamage(kappa[p], eps);
            kappa[p] = k > epsP ? k : kappa[p];
            const double r = hillerborg::forceRatio(eps, k, epsP, epsR[p]);
            const double Fl = s.elasticForcePerLength(EA) * r;
            gx = Fl * s.dx, gy = Fl * s.dy, gz = Fl * s.dz;
            return dashpotRatio(k, epsP, eps);
        }
    };
    Rows rows() { return {kappa.data(), epsR.data(), epsP, stretchOfStrain(epsP), softening.data()}; }

    // Bar b alone, at strain eps, with the damage of the last force evaluation.
    double force(std::int64_t b, double EA, double eps) const {
        return hillerborg::axialForce(eps, kappa[b], EA, epsP, epsR[b]);
    }
    // Energies and damage state of bar b at strain eps. kappa is the damage
    // reached at the last force evaluation; the bar can only have gone further
    // since, so take the larger.
    double stored(std::int64_t b, double EA, double L, double eps) const {
        return hillerborg::storedEnergy(eps, hillerborg::updateDamage(kappa[b], eps), EA, epsP, epsR[b], L);
    }
    double dissipated(std::int64_t b, double EA, double L, double eps) const {
        return hillerborg::dissipatedEnergy(hillerborg::updateDamage(kappa[b], eps), EA, epsP, epsR[b], L);
    }
    // A_f G_f, or 1/2 L EA eps_p^2 for a bar clamped to perfectly brittle.
    double ruptureEnergy(std::int64_t b, double EA, double L) const {
        return hillerborg::triangleEnergy(EA, epsP, epsR[b], L);
    }
    DamageState damage(std::int64_t b, double eps = 0) const {
        return ldem::damageState(hillerborg::updateDamage(kappa[b], eps), epsP, epsR[b]);
    }
    // A broken bar (kappa >= eps_r) carries no tension, ever again.
    bool intact(std::int64_t b) const { return kappa[b] < epsR[b]; }
    // Owned bars whose eps_r < eps_p was raised to eps_p (perfectly brittle).
    std::int64_t clampedOwnedBars() const { return clamped_; }

    // The state a checkpoint keeps (its keys in checkpoint.npz), and the constants.
    std::vector<std::pair<std::string, const std::vector<double>*>> arrays() const {
        return {{"kappa", &kappa}, {"eps_r", &epsR}};
    }
    std::vector<std::pair<std::string, std::vector<double>*>> arrays() { return {{"kappa", &kappa}, {"eps_r", &epsR}}; }
    std::vector<std::uint8_t>& softeningRows() { return softening; }
    const std::vector<std::uint8_t>& softeningRows() const { return softening; }
    std::vector<std::pair<std::string, double>> constants() const { return {{"eps_p", epsP}}; }

    // Its one-bar functions for Python: def(name, doc, function, argument names...).
    template <class Def>
    static void singles(Def def) {
        def("hillerborg_force", "axial force [N] at strain eps with damage kappa >= eps (tension positive)",
            &hillerborg::axialForce, "eps", "kappa", "EA", "eps_p", "eps_r");
        def("dissipated_energy", "energy a bar has dissipated at damage kappa [J]", &hillerborg::dissipatedEnergy,
            "kappa", "EA", "eps_p", "eps_r", "L");
        def("limit_strain", "(eps_r, clamped): the limit strain of a bar of fracture area Af and energy Gf",
            +[](double Af, double Gf, double EA, double epsP, double L) {
                const hillerborg::LimitStrain ls = hillerborg::limitStrain(Af, Gf, EA, epsP, L);
                return std::make_pair(ls.epsR, ls.clamped);
            },
            "Af", "Gf", "EA", "eps_p", "L");
    }

private:
    std::int64_t clamped_ = 0;
};

}  // namespace ldem
