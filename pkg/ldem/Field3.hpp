// Three components per node (or per bar) in structure-of-arrays form: the
// displacements, velocities and forces the loops stream through.
#pragma once
#include <cstdint>
#include <vector>

namespace ldem {

struct Field3 {
    std::vector<double> x, y, z;
    explicit Field3(std::int64_t n = 0) : x(n, 0.0), y(n, 0.0), z(n, 0.0) {}
};

}  // namespace ldem
