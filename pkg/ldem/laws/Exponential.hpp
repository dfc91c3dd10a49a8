// An exponential softening law for a bar (a SecantLaw: laws/SecantLaw.hpp),
// the exponential softening of many damage and cohesive models of concrete.
//
//        F
//   EA eps_p |    /\             tension: elastic up to eps_p, then
//            |   /  `.           F = F_p exp(-(kappa - eps_p)/eps_s),  F_p = EA eps_p,
//            |  /     `-.        cut at eps_r where F = c F_p (c = kTailForce):
//   c Fp     | /         ``-|    the bar breaks there, its force drops to zero.
//   ---------+/-------------+--eps
//           /|  eps_p       eps_r
//
// In strain, for a bar of length L (W = A_f G_f / L):
//   eps_r = eps_p + eps_s ln(1/c),
//   area under the envelope to eps_r: A_r = 1/2 F_p eps_p + F_p eps_s (1 - c),
// and the drop at eps_r dissipates the energy stored on the secant, so that a
// broken bar has dissipated L A_r. The tail beyond the cut is folded into
// eps_s: A_r = W exactly, eps_s = (W - 1/2 F_p eps_p) / (F_p (1 - c)), longer by
// 1/(1 - c) than the uncut law's. The drop's share of A_f G_f is
// 1/2 c F_p eps_r / W: 2.3 % for a normal bar of the study's material at the mean G_f
// (eps_r = 57 eps_p there).
// Damage kappa = largest strain; below kappa the secant to the origin; compression elastic.
// W < 1/2 F_p eps_p (a snap-back): perfectly brittle, as the triangle (counted clamped).
#pragma once
#include <array>
#include <cmath>
#include <tuple>

#include "ldem/laws/SecantLaw.hpp"

namespace ldem {

namespace exponential {

// The force at the cut over the peak force: small, and the drop there dissipates 1/2 c F_p eps_r L.
constexpr double kTailForce = 0.01;

struct SofteningStrains {
    double epsS, epsR;  // decay strain, strain of rupture
    bool clamped;       // perfectly brittle: the envelope would snap back
};

// eps_s and eps_r of a bar of fracture area Af and energy Gf (header comment).
inline SofteningStrains softeningStrains(double Af, double Gf, double EA, double epsP, double L) {
    const double W = Af * Gf / L, Fp = EA * epsP;
    if (W < 0.5 * Fp * epsP) return {0.0, epsP, true};
    const double epsS = (W - 0.5 * Fp * epsP) / (Fp * (1 - kTailForce));
    return {epsS, epsP - epsS * std::log(kTailForce), false};
}

// Secant ratio s(kappa) = F_envelope(kappa) / (EA kappa): 1 up to eps_p, 0 from eps_r.
inline double secantRatio(double kappa, double epsP, double epsS, double epsR) {
    const double r = epsP * std::exp(-(kappa - epsP) / epsS) / kappa;
    return kappa <= epsP ? 1.0 : (kappa < epsR ? r : 0.0);
}

// Axial force (tension positive) at strain eps with damage kappa >= eps.
inline double exponentialForce(double eps, double kappa, double EA, double epsP, double epsS, double epsR) {
    return EA * eps * (eps > 0.0 ? secantRatio(kappa, epsP, epsS, epsR) : 1.0);
}

// Energy dissipated at damage kappa: L (area under the envelope to kappa - 1/2 F(kappa) kappa),
//   eps_p < kappa < eps_r:  A = 1/2 F_p eps_p + F_p eps_s (1 - exp(-(kappa - eps_p)/eps_s)),
//   kappa >= eps_r:         A = 1/2 F_p eps_p + F_p eps_s (1 - c) and F = 0: D = A_f G_f.
inline double exponentialDissipated(double kappa, double EA, double epsP, double epsS, double epsR, double L) {
    if (kappa <= epsP) return 0.0;
    const double Fp = EA * epsP;
    if (kappa >= epsR) return L * (0.5 * Fp * epsP + Fp * epsS * (1 - kTailForce));
    const double decay = std::exp(-(kappa - epsP) / epsS);
    return L * (0.5 * Fp * epsP - Fp * epsS * std::expm1(-(kappa - epsP) / epsS) - 0.5 * Fp * decay * kappa);
}

}  // namespace exponential

// The exponential envelope as a shape of SecantLaw: eps_s and eps_r per bar, no constants of its own.
struct ExponentialShape : NoParams {
    static constexpr const char* name = "exponential";
    static constexpr std::array<const char*, 1> kBarParams{"eps_s"};
    using Bar = std::array<double, 1>;

    static Realised<1> realise(double Af, double Gf, double EA, double epsP, double L, const Params&) {
        const exponential::SofteningStrains s = exponential::softeningStrains(Af, Gf, EA, epsP, L);
        return {s.epsR, {s.epsS}, s.clamped};
    }
    static double secantRatio(double kappa, double epsP, double epsR, const Bar& b, const Params&) {
        return exponential::secantRatio(kappa, epsP, b[0], epsR);
    }
    static double dissipated(double kappa, double EA, double epsP, double epsR, const Bar& b, const Params&, double L) {
        return exponential::exponentialDissipated(kappa, EA, epsP, b[0], epsR, L);
    }

    template <class Def>
    static void singles(Def def) {
        def("exponential_force", "exponential law: axial force [N] at strain eps with damage kappa >= eps",
            &exponential::exponentialForce, "eps", "kappa", "EA", "eps_p", "eps_s", "eps_r");
        def("exponential_dissipated_energy", "exponential law: energy a bar has dissipated at damage kappa [J]",
            &exponential::exponentialDissipated, "kappa", "EA", "eps_p", "eps_s", "eps_r", "L");
        def("exponential_softening_strains",
            "exponential law: (eps_s, eps_r, clamped) of a bar of fracture area Af, energy Gf",
            +[](double Af, double Gf, double EA, double epsP, double L) {
                const exponential::SofteningStrains s = exponential::softeningStrains(Af, Gf, EA, epsP, L);
                return std::make_tuple(s.epsS, s.epsR, s.clamped);
            },
            "Af", "Gf", "EA", "eps_p", "L");
    }
};

using ExponentialLaw = SecantLaw<ExponentialShape>;

}  // namespace ldem
