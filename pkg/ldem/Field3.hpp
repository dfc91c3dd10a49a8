// Three components per node (or per bar) in structure-of-arrays form: the
// displacements, velocities and forces the loops stream through.
#pragma once
#include <cstdint>
#include <vector>

namespace ldem {

struct Field3 {
    std::vector<double> x, y, z;
    explicit Field3(std::int64_t n = 0) : x(n, 0.0), y(n, 0.0), z(n, 0.0) {}
    std::vector<double>& operator[](int dim) { return dim == 0 ? x : dim == 1 ? y : z; }  // 0: x, 1: y, 2: z
    const std::vector<double>& operator[](int dim) const { return dim == 0 ? x : dim == 1 ? y : z; }
};

}  // namespace ldem
