// Eight doubles in one register (GCC's and Clang's vector extension), for the
// two loops whose plain form the compiler does not keep in registers: the node
// sums (InternalForces.cpp), kept in registers over all the bars of a block of
// nodes, and the integration (Integrator.cpp), whose damping work adds up in
// eight lanes. An operation on a Block is the same operation on each lane, in
// the same order on any machine (the compiler splits it into the vectors the
// machine has), so sums stay bit-identical for any thread count.
#pragma once
#include <cstdint>

namespace ldem {

constexpr int kBlock = 8;
typedef double Block __attribute__((vector_size(kBlock * sizeof(double))));
typedef std::int64_t BlockMask __attribute__((vector_size(kBlock * sizeof(std::int64_t))));

// Loads and stores without alignment (a Block's type that may sit anywhere
// and alias doubles). There are no partial ones: a loop over the lanes would
// become a call of memcpy; the loops shift their last block or finish one by one.
typedef double UnalignedBlock __attribute__((vector_size(kBlock * sizeof(double)), aligned(sizeof(double)), may_alias));
inline Block loadBlock(const double* p) { return *reinterpret_cast<const UnalignedBlock*>(p); }
inline void storeBlock(const Block& b, double* p) { *reinterpret_cast<UnalignedBlock*>(p) = b; }

}  // namespace ldem
