// Is the specimen still in one piece? (LDEM_SPEC section 6: U_num is the
// fracture energy dissipated up to the moment when no chain of unbroken bars
// joins the upper face to the lower face.)
//
// A broken bar (kappa >= eps_r) carries no tension, ever again; any other bar
// can. After the peak, nodes hang on diagonals and free lateral DOFs, a truss
// mechanism that carries almost no force until its bars straighten, so the
// load is lost long before the specimen is in two pieces: only connectivity
// tells separation. Union-find over the intact bars: O(bars), about as much
// work as one or two time steps, so the run checks it only every so often.
#pragma once
#include <cstdint>
#include <vector>

#include "ldem/InternalForces.hpp"
#include "ldem/Lattice.hpp"

namespace ldem {

// 1 for every bar that can still carry tension (kappa < eps_r).
std::vector<std::uint8_t> intactBars(const BarState& bars);

// True if some chain of intact bars joins a node of `a` to a node of `b`.
bool nodesJoined(const Lattice& lat, const std::vector<std::uint8_t>& intact, const std::vector<std::int32_t>& a,
                 const std::vector<std::int32_t>& b);

}  // namespace ldem
