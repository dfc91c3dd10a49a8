// What every bar law provides (laws/Hillerborg.hpp is one; laws/Registry.hpp
// lists them and checks the main members at compile time; laws/SecantLaw.hpp
// writes them once for the laws that unload on a secant). A law is one class
// holding its constants and the state of every bar, built from the lattice,
// the material and the random G_f field:
//
//   static constexpr const char* name   its choice of the `law` parameter (unique);
//   Law(lat, material, Gf)         realises the per-bar parameters (e.g. limit strains);
//   rows()                         the row functor of the force loop (below), with its
//                                  elastic fast path;
//   force(b, EA, eps)              the axial force of bar b alone at strain eps [N];
//   stored(b, EA, L, eps), dissipated(b, EA, L, eps)   its energies at strain eps [J];
//   damage(b, eps = 0)             its DamageState (at strain eps, or as it stands);
//   ruptureEnergy(b, EA, L)        the energy bar b dissipates when it breaks [J];
//   intact(b)                      bar b can still carry tension;
//   clampedOwnedBars()             bars of this rank whose parameters had to be clamped;
//   arrays() / softeningRows()     the state a checkpoint stores, by name (Python's
//                                  sim.law_state(), bars.vtu): first "kappa", the damage
//                                  (the largest strain), last "eps_r", the strain of rupture;
//   constants()                    the constants common to all bars, by name;
//   static singles(def)            its one-bar functions for Python (LAMMPS's `single`).
//
// The row functor: for bar row r, whose bars are first, first + 1, ...,
// rows().forRow(r, first) gives the law of that row (state pointers advanced,
// so that the loops index them from 0):
//   rowLaw.path()          the row's RowPath (below), kept by the law (checkpointed);
//   rowLaw.setPath(path)   moves the row on to a slower path (never back);
//   rowLaw.elastic(p, fam, EA, dux, duy, duz, gx, gy, gz)   writes in g the force
//       on bar p's A node as if the bar were elastic, and returns a number > 0
//       if it may not be (the row then goes through the law);
//   rowLaw(p, EA, s, gx, gy, gz)   the law with damage, from the bar's stretch s
//       (a SeriesStretch or a BarStretch: strain() and elasticForcePerLength(EA));
//       returns the ratio r of the bar's dashpot (dashpotRatio below).
// du = u(B) - u(A); large displacements: the force acts along d = d0 + du.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "ldem/Lattice.hpp"

namespace ldem {

enum class DamageState : unsigned char { Undamaged = 0, Damaged = 1, Broken = 2 };

// The damage state of a bar whose law is elastic up to eps_p and carries no
// tension from eps_r on, at damage kappa (the largest strain reached).
inline DamageState damageState(double kappa, double epsP, double epsR) {
    if (kappa >= epsR) return DamageState::Broken;
    return kappa > epsP ? DamageState::Damaged : DamageState::Undamaged;
}

// The ratio r of a bar's dashpot (BarDashpot.hpp), at damage kappa and strain
// eps: 1 while a bar that has left its elastic branch is in compression (its
// crack closed: there the faces clap), else 0, so that no dashpot bridges a
// crack that opens (in tension it held the load of a fast tail up: results/dynamics/README.md).
inline double dashpotRatio(double kappa, double epsP, double eps) { return kappa > epsP && eps < 0.0 ? 1.0 : 0.0; }

// The path of a row of bars through the force loop (InternalForces.hpp): the
// elastic fast path while every bar is elastic; then the law, from the
// series stretch while every bar's |x| is within kElasticSeriesLimit; else
// the law from the exact stretch. A row only moves on to a slower path.
enum RowPath : std::uint8_t { kElasticPath = 0, kSeriesPath = 1, kExactPath = 2 };

// The stretch of a bar from its reference vector d0 (length L) and the
// relative displacement du of its ends, without cancellation:
//   n = l^2 - L^2 = 2 d0.du + du.du,   x = n / L^2 = (l/L)^2 - 1,
//   l = L sqrt(1 + x),   eps = (l - L)/L = sqrt(1 + x) - 1,
//   F/l = EA eps r / l,  r = F/(EA eps) the law's force ratio (1 while the bar is elastic).
inline double stretchN(const BarFamily& fam, double dux, double duy, double duz) {
    return 2 * (fam.d0[0] * dux + fam.d0[1] * duy + fam.d0[2] * duz) + dux * dux + duy * duy + duz * duz;
}

// Exact, with one square root and one division for both the strain and F/l:
//   w = 1 / ((l + L) L l),   eps = n / ((l + L) L) = n w l,   EA eps / l = EA n w.
struct BarStretch {
    double dx, dy, dz;  // current bar vector d0 + du [m]
    double l, n, w;
    double strain() const { return n * w * l; }
    double elasticForcePerLength(double EA) const { return EA * n * w; }
};

inline BarStretch barStretch(const BarFamily& fam, double dux, double duy, double duz) {
    const double dx = fam.d0[0] + dux, dy = fam.d0[1] + duy, dz = fam.d0[2] + duz;
    const double l = std::sqrt(dx * dx + dy * dy + dz * dz);
    return {dx, dy, dz, l, stretchN(fam, dux, duy, duz), 1 / ((l + fam.L) * fam.L * l)};
}

// Without a square root or a division, for |x| <= kElasticSeriesLimit:
//   EA eps / l = (EA/L) (1 - (1 + x)^(-1/2)) = (EA/L) x h(x),   eps = sqrt(1 + x) - 1 = x e(x),
//   h(x) = 1/2 - 3/8 x + 5/16 x^2 - 35/128 x^3 + 63/256 x^4 - 231/1024 x^5 + 429/2048 x^6 - ...,
//   e(x) = 1/2 - 1/8 x + 1/16 x^2 - 5/128 x^3 + 7/256 x^4 - 21/1024 x^5 + 33/2048 x^6 - ...
// (binomial series). Cut after x^6, h is off by less than 0.4 |x|^7 of itself
// and e by less than 0.03 |x|^7: below 1e-17 for |x| <= 4e-3 (|eps| <= 2e-3),
// beyond any strain of an unbroken bar of concrete in tension. The square root
// and the divisions cost about as much as the rest of the bar (README, Performance).
constexpr double kElasticSeriesLimit = 4e-3;

inline double elasticSeries(double x) {
    return 0.5 + x * (-0.375 + x * (0.3125 + x * (-0.2734375 + x * (0.24609375 + x * (-0.2255859375 +
                                                                                     x * 0.20947265625)))));
}
inline double strainSeries(double x) {
    return 0.5 + x * (-0.125 + x * (0.0625 + x * (-0.0390625 + x * (0.02734375 + x * (-0.0205078125 +
                                                                                    x * 0.01611328125)))));
}

struct SeriesStretch {
    double dx, dy, dz;  // current bar vector d0 + du [m]
    double x, invL;  // the stretch x; 1/L
    double strain() const { return x * strainSeries(x); }
    double elasticForcePerLength(double EA) const { return EA * invL * x * elasticSeries(x); }
};

inline SeriesStretch seriesStretch(const BarFamily& fam, double dux, double duy, double duz) {
    return {fam.d0[0] + dux, fam.d0[1] + duy, fam.d0[2] + duz, stretchN(fam, dux, duy, duz) * fam.invL2, fam.invL};
}

// x of eps_p: eps > eps_p  <=>  x > (1 + eps_p)^2 - 1.
inline double stretchOfStrain(double eps) { return eps * (2 + eps); }

// The elastic fast path of the laws that are linear elastic up to a strain
// eps_p (both laws here): writes in g the force on node A of an elastic bar
// (tension pulls A along +d) and returns a number > 0 if the bar may not be
// elastic (x above xP, the stretch of eps_p) or is beyond the series: rowLaw.elastic.
inline double elasticBarForce(const BarFamily& fam, double EA, double xP, double dux, double duy, double duz,
                              double& gx, double& gy, double& gz) {
    const SeriesStretch s = seriesStretch(fam, dux, duy, duz);
    const double Fl = s.elasticForcePerLength(EA);
    gx = Fl * s.dx, gy = Fl * s.dy, gz = Fl * s.dz;
    return std::max(s.x - xP, std::abs(s.x) - kElasticSeriesLimit);
}

}  // namespace ldem
