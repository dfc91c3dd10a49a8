// The constitutive law of one bar: Hillerborg's triangle (LDEM_SPEC section 3):
// its pure functions and its shape; the per-bar state, the row functor of the
// force loop and the realisation from the random G_f are SecantLaw's
// (laws/SecantLaw.hpp; the interface: laws/BarLaw.hpp).
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
#include <array>
#include <utility>

#include "ldem/laws/SecantLaw.hpp"

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

// The triangle as a shape of SecantLaw (laws/SecantLaw.hpp): eps_r alone per bar.
struct HillerborgShape : NoParams {
    static constexpr const char* name = "hillerborg";
    static constexpr std::array<const char*, 0> kBarParams{};
    using Bar = std::array<double, 0>;

    static Realised<0> realise(double Af, double Gf, double EA, double epsP, double L, const Params&) {
        const hillerborg::LimitStrain ls = hillerborg::limitStrain(Af, Gf, EA, epsP, L);
        return {ls.epsR, {}, ls.clamped};
    }
    static double secantRatio(double kappa, double epsP, double epsR, Bar, const Params&) {
        return hillerborg::secantRatio(kappa, epsP, epsR);
    }
    static double dissipated(double kappa, double EA, double epsP, double epsR, Bar, const Params&, double L) {
        return hillerborg::dissipatedEnergy(kappa, EA, epsP, epsR, L);
    }

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
};

using HillerborgLaw = SecantLaw<HillerborgShape>;

}  // namespace ldem
