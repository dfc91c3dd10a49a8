#include "ldem/Material.hpp"

namespace ldem {

void Material::validate() const {
    LDEM_MATERIAL_PARAMETERS(LDEM_CHECK_MEMBER)
    // The Weibull's variable part has the mean E[G_f] - Gf_min: none is left at Gf_min >= Gf_mean.
    if (GfCV > 0 && !(GfMin < GfMean))
        throw std::invalid_argument("Gf_min " + formatNumber(GfMin) + " N/m must be below Gf_mean " +
                                    formatNumber(GfMean) + " N/m: the Weibull keeps the mean with its CV only above "
                                    "its lower bound");
}

}  // namespace ldem
