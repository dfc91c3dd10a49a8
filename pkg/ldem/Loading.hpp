// The loading of the cube tests (LDEM_SPEC section 6): its parameters. The
// drives are dynamic parts (dynamics/Registry.hpp): a displacement U(t) that
// grows smoothly from rest (dynamics/ConstantRateDrive.hpp; the specimen says
// which DOFs follow it and with which weights, Specimen.hpp), after the load
// loss fixed or adaptive (tail_drive: dynamics/AdaptiveDrive.hpp), or a servo
// that holds an opening to a program (dynamics/ServoDrive.hpp).
#pragma once
#include "ldem/Parameters.hpp"

namespace ldem {

enum class LoadShape { Uniform, Triangular };
enum class TailDrive { Fixed, Adaptive };

// LDEM_LOADING_PARAMETERS (Parameters.hpp): load shape, strain rate, smooth
// start, lateral DOFs of the faces, speed-up after load loss.
struct LoadingParams {
    LDEM_LOADING_PARAMETERS(LDEM_DECLARE_MEMBER)
    void validate() const;
};

}  // namespace ldem
