#include "ldem/Material.hpp"

namespace ldem {

void Material::validate() const { LDEM_MATERIAL_PARAMETERS(LDEM_CHECK_MEMBER) }

}  // namespace ldem
