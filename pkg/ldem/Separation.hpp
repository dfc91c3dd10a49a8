// Is the specimen still in one piece? (LDEM_SPEC section 6: U_num is the
// fracture energy dissipated up to the moment when no chain of unbroken bars
// joins the upper face to the lower face.)
//
// A broken bar carries no tension, ever again; any other bar can (the bar
// law tells which: laws/). After the peak, nodes hang on diagonals and free lateral DOFs, a truss
// mechanism that carries almost no force until its bars straighten, so the
// load is lost long before the specimen is in two pieces: only connectivity
// tells separation. Union-find over the intact bars: O(bars), about as much
// work as one or two time steps, so the run checks it only every so often.
#pragma once
#include <cstdint>
#include <vector>

#include "ldem/Lattice.hpp"

namespace ldem {

// 1 for every bar of lat that can still carry tension (the bar law's intact(b)).
template <class Law>
std::vector<std::uint8_t> intactBars(const Lattice& lat, const Law& law) {
    std::vector<std::uint8_t> intact(lat.numBars());
#pragma omp parallel for schedule(static)
    for (std::int64_t b = 0; b < std::int64_t(intact.size()); ++b) intact[b] = law.intact(b);
    return intact;
}

// True if some chain of intact bars joins a node of `a` to a node of `b`.
bool nodesJoined(const Lattice& lat, const std::vector<std::uint8_t>& intact, const std::vector<std::int32_t>& a,
                 const std::vector<std::int32_t>& b);

}  // namespace ldem
