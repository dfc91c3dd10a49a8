// The loading of the cube tests (LDEM_SPEC section 6): its parameters, the
// registered drives' among them (dynamics/Registry.hpp). A drive moves the
// specimen's prescribed DOFs (Specimen.hpp) by U(t), from rest.
#pragma once
#include "ldem/Parameters.hpp"
#include "ldem/dynamics/Registry.hpp"

// The loading: its own parameters, the drive's program and choice, then every drive's list in registry order.
#define LDEM_LOADING_PARAMETERS(X)                                                                           \
    X(LoadShape, shape, "load", LoadShape::Uniform, "", Domain::choices({"uniform", "triangular"}),          \
      "upper-face displacement: uniform or triangular")                                                      \
    LDEM_DRIVE_PARAMETERS(X)                                                                                 \
    X(bool, topLateralFree, "top_lateral", true, "", Domain::choices({"fixed", "free"}),                     \
      "lateral DOFs of the upper nodes: free or fixed")                                                      \
    X(bool, bottomLateralFree, "bottom_lateral", false, "", Domain::choices({"fixed", "free"}),              \
      "lateral DOFs of the lower nodes: fixed, or free (rollers)")                                           \
    X(DriveId, tailDrive, "tail_drive", driveNamed("adaptive"), "", Domain::choices(driveNames()), driveHelp()) \
    LDEM_SPEEDUP_PARAMETERS(X)                                                                               \
    LDEM_DRIVES(LDEM_PART_LIST, X)

namespace ldem {

enum class LoadShape { Uniform, Triangular };

struct LoadingParams {
    LDEM_LOADING_PARAMETERS(LDEM_DECLARE_MEMBER)
    void validate() const;
};

}  // namespace ldem
