// The bounds that tie parameters to one another (a parameter's own bounds are
// its domain in Parameters.hpp; its help states these rules too). Checked
// before anything is allocated: CubeTestParams::validate, a specimen file's
// parameters once its L0 is known, and the Simulation's constructor.
#pragma once
#include <cstdint>
#include <string>

#include "ldem/Loading.hpp"
#include "ldem/Material.hpp"
#include "ldem/RunParams.hpp"

namespace ldem {

// The G_f below which a bar is perfectly brittle: Hillerborg's triangle,
// eps_r = 2 A_f G_f / (EA eps_p L), falls below eps_p when
//   G_f < G_b = EA eps_p^2 L / (2 A_f),
// normal bars: E phi eps_p^2 L0 / (2 c_a); diagonals (A_d, sqrt(3)/2 L0, c_a (1.15 L0)^2) a little lower.
double brittleFractureEnergy(const Material& m, double L0, bool diagonal);
// The limit strain of a normal bar of the mean G_f: eps_r = 2 c_a G_f / (E phi eps_p L0).
double meanLimitStrain(const Material& m, double L0);

// Throws std::invalid_argument, naming the parameters and the rule, when
// - every bar is brittle by construction: G_f is the same in every bar (Gf_cv 0) and below both families' G_b;
// - the mean bar's limit strain eps_r is above 1 (the lattice's geometry is that of small strains);
// - the smooth start outlasts eps_p / strain_rate: its mean strain at the end, strain_rate ramp_time / 2,
//   would be above eps_p / 2, so that the bars could crack during the ramp.
void checkRelations(const Material& m, const LoadingParams& l, const RunParams& r, double L0);

// Throws std::invalid_argument when every one of the lattice's bars drew a G_f
// below its brittle bound (clamped of bars): no bar left to soften, no model of concrete.
void refuseAllBrittle(std::int64_t clamped, std::int64_t bars, const Material& m, double L0);

// The time step: r.dt, refused above the stability limit (its message names the limit's factors:
// dt_safety, the dampings' stepFactor, omega_max [rad/s]), or the limit itself when r.dt is 0.
double chosenTimeStep(const RunParams& r, double limit, double stepFactor, double omegaMax);

// A warning ("" if none) when the bars of the mean G_f are perfectly brittle:
// a share of the bars by construction, not by the random draw alone.
std::string brittleWarning(const Material& m, double L0);

}  // namespace ldem
