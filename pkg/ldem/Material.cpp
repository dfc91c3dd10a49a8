#include "ldem/Material.hpp"

namespace ldem {

namespace {
void require(bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument(what);
}
}  // namespace

void Material::validate() const {
    require(std::isfinite(E) && E > 0, "E must be positive (got " + std::to_string(E) + " Pa)");
    // nu >= 0.5 is incompressible and delta = 9nu/(4-8nu) blows up; nu < 0 makes
    // the diagonal area negative: the lattice cannot represent either.
    require(nu >= 0.0 && nu < 0.5, "nu must be in [0, 0.5) (got " + std::to_string(nu) + ")");
    require(std::isfinite(rho) && rho > 0, "rho must be positive (got " + std::to_string(rho) + " kg/m^3)");
    require(std::isfinite(GfMean) && GfMean > 0, "mean G_f must be positive (got " + std::to_string(GfMean) + " N/m)");
    require(std::isfinite(GfCV) && GfCV >= 0, "CV of G_f must be >= 0 (got " + std::to_string(GfCV) + ")");
    require(GfCV <= 10.0, "CV of G_f above 1000% is not supported (got " + std::to_string(GfCV) + ")");
    require(std::isfinite(corrLength) && corrLength >= 0, "correlation length must be >= 0 (got " + std::to_string(corrLength) + " m)");
    require(std::isfinite(epsP) && epsP > 0, "eps_p must be positive (got " + std::to_string(epsP) + ")");
    require(std::isfinite(ca) && ca > 0, "c_a must be positive (got " + std::to_string(ca) + ")");
}

}  // namespace ldem
