// A bilinear softening law for a bar (the interface: laws/BarLaw.hpp), after
// the bilinear cohesive law of concrete: fib Model Code 2010, eqs. 5.1-10/11
// (sigma_k = 0.2 f_t at w_1 = G_F/f_t, zero at w_c = 5 G_F/f_t), and Bazant &
// Becq-Giraudon, Cem. Concr. Res. 32 (2002) 529 (the initial slope carries the
// initial fracture energy G_f, the tail the rest of the total G_F; G_f/G_F ~ 0.4-0.6).
//
//        F
//   EA eps_p |    /\             tension: elastic up to eps_p, then the initial
//            |   /  \            line (that of a triangle of area g A_f G_F, zero at
//   s_k Fp   |  /    \__         eps_1) down to the kink (eps_k, s_k EA eps_p), then
//            | /        ``--__   the tail to zero at eps_r, placed so that the whole
//   ---------+/-------------``-eps  area is A_f G_F (G_F: the bar's value of the G_f field).
//           /|  eps_p eps_k  eps_r
//
// In strain, for a bar of length L (W = A_f G_F / L, Fp = EA eps_p):
//   eps_1 = 2 g W / Fp,   eps_k = eps_p + (1 - s_k)(eps_1 - eps_p),
//   eps_r = eps_k + 2 (W - A(eps_k)) / (s_k Fp),  A(eps_k) = area under the envelope to eps_k.
// MC2010 is g = 0.625, s_k = 0.2 (its initial line reaches zero at 1.25 G_F/f_t).
// g = 1 puts the kink on the triangle's line: the envelope is Hillerborg's triangle.
// Damage kappa = largest strain; below kappa the secant to the origin; compression elastic.
// Snap-back: eps_1 < eps_p drops the force at eps_p straight to the kink (eps_1 = eps_p),
// and 2 W / Fp < eps_p makes the bar perfectly brittle as the triangle does (both counted clamped).
#pragma once
#include <algorithm>
#include <cstdint>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "ldem/Lattice.hpp"
#include "ldem/Material.hpp"
#include "ldem/laws/BarLaw.hpp"

namespace ldem {

namespace bilinear {

struct KinkStrains {
    double epsK, epsR;  // strains of the kink and of zero force
    bool clamped;       // a snap-back was removed
};

// Area (per unit length, F x strain) under the envelope up to the kink:
//   1/2 Fp eps_p + 1/2 (1 + s_k) Fp (eps_k - eps_p).
inline double kinkArea(double Fp, double epsP, double sK, double epsK) {
    return 0.5 * Fp * epsP + 0.5 * (1 + sK) * Fp * (epsK - epsP);
}

// Area under the whole envelope: A(eps_k) + 1/2 s_k Fp (eps_r - eps_k) = W (1/2 Fp eps_p for
// a perfectly brittle bar, eps_k = eps_r = eps_p).
inline double envelopeArea(double Fp, double epsP, double sK, double epsK, double epsR) {
    return kinkArea(Fp, epsP, sK, epsK) + 0.5 * sK * Fp * (epsR - epsK);
}

// The kink and the end of a bar of fracture area Af, energy GF, of which g GF
// under the initial line, kink stress ratio sK (header comment).
inline KinkStrains kinkStrains(double Af, double GF, double EA, double epsP, double L, double g, double sK) {
    const double W = Af * GF / L, Fp = EA * epsP;
    if (2 * W / Fp < epsP) return {epsP, epsP, true};  // perfectly brittle, as the triangle
    const double eps1 = 2 * g * W / Fp;
    const double epsK = epsP + (1 - sK) * std::max(eps1 - epsP, 0.0);
    return {epsK, epsK + 2 * (W - kinkArea(Fp, epsP, sK, epsK)) / (sK * Fp), eps1 < epsP};
}

// Envelope force over EA eps_p at strain kappa > eps_p: the initial line to
// the kink, then the tail (never below 0). Selects, without branches, so that
// the bar loop vectorizes; a division by zero (eps_k = eps_p, or a perfectly
// brittle bar) lands in an unselected or negative value.
inline double envelopeOverPeak(double kappa, double epsP, double sK, double epsK, double epsR) {
    const double initial = 1 - (1 - sK) * (kappa - epsP) / (epsK - epsP);
    const double tail = sK * (epsR - kappa) / (epsR - epsK);
    return kappa <= epsK ? initial : (tail > 0.0 ? tail : 0.0);
}

// Secant ratio s(kappa) = F_envelope(kappa) / (EA kappa): 1 up to eps_p.
inline double secantRatio(double kappa, double epsP, double sK, double epsK, double epsR) {
    return kappa <= epsP ? 1.0 : envelopeOverPeak(kappa, epsP, sK, epsK, epsR) * epsP / kappa;
}

// F / (EA eps) at strain eps with damage kappa >= eps: s(kappa) in tension, 1 in compression.
inline double forceRatio(double eps, double kappa, double epsP, double sK, double epsK, double epsR) {
    return eps > 0.0 ? secantRatio(kappa, epsP, sK, epsK, epsR) : 1.0;
}

// Axial force (tension positive) at strain eps with damage kappa >= eps.
inline double bilinearForce(double eps, double kappa, double EA, double epsP, double sK, double epsK, double epsR) {
    return EA * eps * forceRatio(eps, kappa, epsP, sK, epsK, epsR);
}

inline double updateDamage(double kappa, double eps) { return std::max(kappa, eps); }

// Energy dissipated at damage kappa: L (area under the envelope to kappa - 1/2 F(kappa) kappa),
// the area under each branch a trapezoid:
//   eps_p < kappa <= eps_k:  A = 1/2 Fp eps_p + 1/2 (Fp + F) (kappa - eps_p)
//   eps_k < kappa <  eps_r:  A = A(eps_k) + 1/2 (s_k Fp + F) (kappa - eps_k)
//   kappa >= eps_r:          A = A(eps_k) + 1/2 s_k Fp (eps_r - eps_k) = W, D = A_f G_F.
inline double bilinearDissipated(double kappa, double EA, double epsP, double sK, double epsK, double epsR, double L) {
    if (kappa <= epsP) return 0.0;
    const double Fp = EA * epsP;
    if (kappa >= epsR) return L * envelopeArea(Fp, epsP, sK, epsK, epsR);
    const double F = Fp * envelopeOverPeak(kappa, epsP, sK, epsK, epsR);
    const double area = kappa <= epsK ? 0.5 * Fp * epsP + 0.5 * (Fp + F) * (kappa - epsP)
                                      : kinkArea(Fp, epsP, sK, epsK) + 0.5 * (sK * Fp + F) * (kappa - epsK);
    return L * (area - 0.5 * F * kappa);
}

}  // namespace bilinear

class BilinearLaw {
public:
    static constexpr const char* name = "bilinear";

    double epsP = 0;           // critical strain (same for all bars)
    double sK = 1;             // kink force over peak force (same for all bars)
    std::vector<double> epsK;  // kink strain of each bar
    std::vector<double> epsR;  // strain of zero force of each bar
    std::vector<double> kappa;  // largest strain, recorded once past eps_p
    std::vector<std::uint8_t> softening;  // per bar row: its RowPath (laws/BarLaw.hpp)

    BilinearLaw() = default;
    // Undamaged bars of lat of material m, each bar's kink and end from its G_F
    // (surface edges carry their share of both EA and A_f).
    BilinearLaw(const Lattice& lat, const Material& m, const std::vector<double>& GF)
        : epsP(m.epsP), sK(m.kinkStress), epsK(lat.numBars()), epsR(lat.numBars()), kappa(lat.numBars(), 0.0),
          softening(lat.barRows.size(), 0) {
        const auto owned = lat.ownedBars();
        for (const BarRow& row : lat.barRows) {
            const BarFamily& fam = lat.families[row.family];
            for (int p = 0; p < row.count; ++p) {
                const std::int64_t b = row.first + p;
                const double share = row.shareAt(p);
                const bilinear::KinkStrains k =
                    bilinear::kinkStrains(fam.Af * share, GF[b], fam.EA * share, epsP, fam.L, m.GfRatio, sK);
                epsK[b] = k.epsK, epsR[b] = k.epsR;
                clamped_ += k.clamped && b >= owned.first && b < owned.second;
            }
        }
    }

    // The row functor (laws/BarLaw.hpp): elastic while eps <= eps_p (a row that
    // never left the elastic path has kappa = 0 throughout: the fast path needs no state).
    struct Rows {
        static constexpr bool kElasticOnly = false;  // (InternalForces.hpp: barLayer)
        double* kappa;
        const double* epsK;
        const double* epsR;
        double epsP, sK, xP;  // xP: the stretch x of eps_p (laws/BarLaw.hpp)
        std::uint8_t* softeningRow;

        Rows forRow(std::int32_t r, std::int64_t first) const {
            Rows row = *this;
            row.kappa += first, row.epsK += first, row.epsR += first, row.softeningRow += r;
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
            const double k = bilinear::updateDamage(kappa[p], eps);
            kappa[p] = k > epsP ? k : kappa[p];
            const double r = bilinear::forceRatio(eps, k, epsP, sK, epsK[p], epsR[p]);
            const double Fl = s.elasticForcePerLength(EA) * r;
            gx = Fl * s.dx, gy = Fl * s.dy, gz = Fl * s.dz;
            return dashpotRatio(k, epsP, eps);
        }
    };
    Rows rows() { return {kappa.data(), epsK.data(), epsR.data(), epsP, sK, stretchOfStrain(epsP), softening.data()}; }

    double force(std::int64_t b, double EA, double eps) const {
        return bilinear::bilinearForce(eps, kappa[b], EA, epsP, sK, epsK[b], epsR[b]);
    }
    // At strain eps: the bar can only have gone past the kappa of the last force evaluation.
    double stored(std::int64_t b, double EA, double L, double eps) const {
        const double k = bilinear::updateDamage(kappa[b], eps);
        return 0.5 * bilinear::bilinearForce(eps, k, EA, epsP, sK, epsK[b], epsR[b]) * eps * L;
    }
    double dissipated(std::int64_t b, double EA, double L, double eps) const {
        return bilinear::bilinearDissipated(bilinear::updateDamage(kappa[b], eps), EA, epsP, sK, epsK[b], epsR[b], L);
    }
    // A_f G_F, or 1/2 L EA eps_p^2 for a bar clamped to perfectly brittle: what
    // the bar dissipates once broken (not D(eps_r), which is 0 where eps_r = eps_p).
    double ruptureEnergy(std::int64_t b, double EA, double L) const {
        return L * bilinear::envelopeArea(EA * epsP, epsP, sK, epsK[b], epsR[b]);
    }
    DamageState damage(std::int64_t b, double eps = 0) const {
        return ldem::damageState(bilinear::updateDamage(kappa[b], eps), epsP, epsR[b]);
    }
    bool intact(std::int64_t b) const { return kappa[b] < epsR[b]; }
    std::int64_t clampedOwnedBars() const { return clamped_; }

    std::vector<std::pair<std::string, const std::vector<double>*>> arrays() const {
        return {{"kappa", &kappa}, {"eps_k", &epsK}, {"eps_r", &epsR}};
    }
    std::vector<std::pair<std::string, std::vector<double>*>> arrays() {
        return {{"kappa", &kappa}, {"eps_k", &epsK}, {"eps_r", &epsR}};
    }
    std::vector<std::uint8_t>& softeningRows() { return softening; }
    const std::vector<std::uint8_t>& softeningRows() const { return softening; }
    std::vector<std::pair<std::string, double>> constants() const { return {{"eps_p", epsP}, {"kink_stress", sK}}; }

    template <class Def>
    static void singles(Def def) {
        def("bilinear_force", "bilinear law: axial force [N] at strain eps with damage kappa >= eps",
            &bilinear::bilinearForce, "eps", "kappa", "EA", "eps_p", "s_k", "eps_k", "eps_r");
        def("bilinear_dissipated_energy", "bilinear law: energy a bar has dissipated at damage kappa [J]",
            &bilinear::bilinearDissipated, "kappa", "EA", "eps_p", "s_k", "eps_k", "eps_r", "L");
        def("bilinear_kink_strains", "bilinear law: (eps_k, eps_r, clamped) of a bar of fracture area Af, energy GF",
            +[](double Af, double GF, double EA, double epsP, double L, double g, double sK) {
                const bilinear::KinkStrains k = bilinear::kinkStrains(Af, GF, EA, epsP, L, g, sK);
                return std::make_tuple(k.epsK, k.epsR, k.clamped);
            },
            "Af", "GF", "EA", "eps_p", "L", "Gf_ratio", "s_k");
    }

private:
    std::int64_t clamped_ = 0;
};

}  // namespace ldem
