// How a run goes: the random specimen, damping, time step, stop rules, records
// and threads (LDEM_RUN_PARAMETERS in Parameters.hpp).
#pragma once
#include "ldem/Parameters.hpp"

namespace ldem {

enum class StopAt { Separation, LoadLoss, Converged, PastPeak };

struct RunParams {
    LDEM_RUN_PARAMETERS(LDEM_DECLARE_MEMBER)
    void validate() const { LDEM_RUN_PARAMETERS(LDEM_CHECK_MEMBER) }
};

}  // namespace ldem
