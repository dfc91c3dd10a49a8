#include "ldem/Relations.hpp"

#include <sstream>
#include <stdexcept>

namespace ldem {

double brittleFractureEnergy(const Material& m, double L0, bool diagonal) {
    const double A = diagonal ? diagonalBarArea(m.nu, L0) : normalBarArea(m.nu, L0);
    const double Af = diagonal ? diagonalFractureArea(m.ca, L0) : normalFractureArea(m.ca, L0);
    const double L = diagonal ? 0.5 * std::sqrt(3.0) * L0 : L0;
    return m.E * A * m.epsP * m.epsP * L / (2 * Af);
}

double meanLimitStrain(const Material& m, double L0) {
    return m.epsP * m.GfMean / brittleFractureEnergy(m, L0, false);  // eps_r / eps_p = G_f / G_b
}

void checkRelations(const Material& m, const LoadingParams& l, const RunParams& r, double L0) {
    std::ostringstream msg;
    msg.precision(3);
    // The relative tail re-centres the mass damping's -D_f m v: with no mass damping it would act on nothing.
    if (r.tailDampingRelative && !(std::uint64_t(r.dampings) & std::uint64_t(dampingsNamed("mass"))))
        throw std::invalid_argument("tail_damping relative re-centres the mass damping, which dampings does not "
                                    "name: add mass to dampings, or leave tail_damping absolute");
    const double Gb = brittleFractureEnergy(m, L0, true), Gn = brittleFractureEnergy(m, L0, false);
    if (m.GfCV == 0 && m.GfMean < std::min(Gb, Gn)) {
        msg << "Gf_mean " << m.GfMean << " N/m (the same in every bar, Gf_cv 0) makes every bar perfectly brittle: "
            << "it is below E A eps_p^2 L / (2 A_f) = " << std::min(Gb, Gn) << " N/m (E, nu, eps_p, c_a and L0 = "
            << L0 << " m); raise Gf_mean or c_a (the bound goes as 1 / c_a)";
        throw std::invalid_argument(msg.str());
    }
    if (const double epsR = meanLimitStrain(m, L0); !(epsR <= 1)) {
        msg << "Gf_mean " << m.GfMean << " N/m gives a bar the limit strain eps_r = 2 c_a G_f / (E phi eps_p L0) = "
            << epsR << ", above 1: the lattice's geometry is that of small strains (at most "
            << Gn / m.epsP << " N/m here)";
        throw std::invalid_argument(msg.str());
    }
    if (l.rampTime > m.epsP / l.strainRate) {
        msg << "ramp_time " << l.rampTime << " s is above eps_p / strain_rate = " << m.epsP / l.strainRate
            << " s: the smooth start must end before the mean strain reaches eps_p / 2, before any bar can crack";
        throw std::invalid_argument(msg.str());
    }
}

std::string brittleWarning(const Material& m, double L0) {
    const double Gn = brittleFractureEnergy(m, L0, false);
    if (!(m.GfMean < Gn)) return "";
    std::ostringstream msg;
    msg.precision(3);
    msg << "Gf_mean " << m.GfMean << " N/m is below E phi eps_p^2 L0 / (2 c_a) = " << Gn
        << " N/m: the bars of the mean G_f are perfectly brittle (eps_r < eps_p), by construction";
    return msg.str();
}

void refuseAllBrittle(std::int64_t clamped, std::int64_t bars, const Material& m, double L0) {
    if (clamped < bars) return;
    throw std::invalid_argument("every bar is perfectly brittle: all " + std::to_string(bars) +
                                " drew a G_f below E A eps_p^2 L / (2 A_f) (" +
                                formatNumber(brittleFractureEnergy(m, L0, false)) + " N/m for a normal bar), with "
                                "Gf_mean " + formatNumber(m.GfMean) + " N/m: raise Gf_mean or c_a (the bound goes as "
                                "1 / c_a)");
}

double chosenTimeStep(const RunParams& r, double limit, double stepFactor, double omegaMax) {
    if (r.dt <= limit) return r.dt > 0 ? r.dt : limit;
    std::ostringstream msg;
    msg << "time step " << r.dt << " s is above the stability limit " << limit << " s (" << r.dtSafety
        << " x 2/omega_max x " << stepFactor << " for zeta_high, omega_max = " << omegaMax << " rad/s)";
    throw std::invalid_argument(msg.str());
}

}  // namespace ldem
