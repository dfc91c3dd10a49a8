#include "ldem/Loading.hpp"

namespace ldem {

void LoadingParams::validate() const { LDEM_LOADING_PARAMETERS(LDEM_CHECK_MEMBER) }

}  // namespace ldem
