// The maximum flow through an undirected graph with integer capacities, from
// a set of source nodes to a set of sink nodes: by the max-flow/min-cut
// theorem, the least total capacity of any set of edges whose removal
// separates the two sets. py/ldem/mincut.py takes it for the cheapest cut of
// a specimen (bars as edges, their rupture energies as capacities): a lower
// bound of its fracture energy at separation.
//
// Push-relabel (Boost.Graph). Each edge {u, v} of capacity c is two arcs,
// u -> v and v -> u, each of capacity c with a reverse arc of capacity 0, as
// push_relabel_max_flow requires; the sources hang on a super-source and the
// sinks on a super-sink, each by an arc of its own edges' capacity. Integers
// keep the flow exact: its value does not depend on the order of the pushes.
#pragma once
#include <cstdint>
#include <vector>

namespace ldem {

// The maximum flow from `sources` to `sinks` over the edges {n1[e], n2[e]} of
// capacity capacity[e] >= 0 between nodes 0 .. nodes - 1. A node in both sets,
// a node out of range or a negative capacity is refused (std::invalid_argument).
std::int64_t maxFlow(std::int64_t nodes, const std::vector<std::int64_t>& n1, const std::vector<std::int64_t>& n2,
                     const std::vector<std::int64_t>& capacity, const std::vector<std::int64_t>& sources,
                     const std::vector<std::int64_t>& sinks);

}  // namespace ldem
