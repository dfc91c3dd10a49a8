// A step's work and the measured groups' reactions, summed per owned layer,
// exchanged once a step and added in layer order: the same sums for any
// number of threads and ranks (Slab.hpp). Per layer m:
//   damping:  the work of the dampings on layer m's nodes and bars (damping(m));
//   external: sum -f w (U(n+1) - U(n-1))/2 over its prescribed DOFs: the drive holds each against the
//             bars with -f over the centred increment (x(n+1) - x(n-1))/2, x = w U;
//   support, loaded: the measured component of f at state n summed over each group's nodes there
//             (supportStress()'s sum, bit for bit: the load cells average it over a record interval).
#pragma once
#include <cstdint>
#include <vector>

#include "ldem/Field3.hpp"
#include "ldem/Lattice.hpp"
#include "ldem/Slab.hpp"
#include "ldem/Specimen.hpp"

namespace ldem {

struct StepSums {
    double damping = 0, external = 0, support = 0, loaded = 0;  // [J], [J], [N], [N]
};

class StepWork {
public:
    StepWork() = default;
    // Each node's owned layer looked up once; pre, support and loaded outlive this (the Simulation's own).
    StepWork(const Lattice& lat, const Prescribed& pre, const std::vector<std::int32_t>& support,
             const std::vector<std::int32_t>& loaded, int dim)
        : pre_(&pre), support_(&support), loaded_(&loaded), dim_(dim), preSlot_(ownedLayerSlots(lat, pre.node)),
          supportSlot_(ownedLayerSlots(lat, support)), loadedSlot_(ownedLayerSlots(lat, loaded)) {}

    // f: the bars' forces at state n; centred: (U(n+1) - U(n-1))/2; damping(m) as above.
    template <class LayerDamping>
    StepSums sum(const Lattice& lat, const Field3& f, double centred, LayerDamping damping) {
        const int owned = lat.ownEnd - lat.ownBegin;
        partial_.assign(4 * std::size_t(owned), 0.0);
        for (int i = 0; i < owned; ++i) partial_[4 * std::size_t(i)] = damping(lat.ownBegin + i);
        const Prescribed& pre = *pre_;
        addBySlot(partial_, 4, 1, preSlot_,
                  [&](std::size_t k) { return -f[pre.dim[k]][pre.node[k]] * pre.weight[k] * centred; });
        const std::vector<double>& fm = f[dim_];
        addBySlot(partial_, 4, 2, supportSlot_, [&](std::size_t k) { return fm[(*support_)[k]]; });
        addBySlot(partial_, 4, 3, loadedSlot_, [&](std::size_t k) { return fm[(*loaded_)[k]]; });
        const std::vector<double> sums = gatherLayerSums(commOf(lat), partial_, 4);
        return {sums[0], sums[1], sums[2], sums[3]};
    }

private:
    const Prescribed* pre_ = nullptr;
    const std::vector<std::int32_t>*support_ = nullptr, *loaded_ = nullptr;
    int dim_ = 0;  // the measured direction
    // Owned layer (- ownBegin) of each prescribed DOF's node, support and loaded node; -1 if not owned.
    std::vector<std::int32_t> preSlot_, supportSlot_, loadedSlot_;
    std::vector<double> partial_;  // 4 per owned layer, kept between steps
};

}  // namespace ldem
