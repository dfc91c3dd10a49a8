#include "ldem/MaxFlow.hpp"

#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/push_relabel_max_flow.hpp>
#include <stdexcept>
#include <string>

namespace ldem {

namespace {
using Traits = boost::adjacency_list_traits<boost::vecS, boost::vecS, boost::directedS>;
using Graph = boost::adjacency_list<
    boost::vecS, boost::vecS, boost::directedS, boost::no_property,
    boost::property<boost::edge_capacity_t, std::int64_t,
                    boost::property<boost::edge_residual_capacity_t, std::int64_t,
                                    boost::property<boost::edge_reverse_t, Traits::edge_descriptor>>>>;

// The arc u -> v of capacity c and its reverse v -> u of capacity 0.
void addArc(Graph& g, std::int64_t u, std::int64_t v, std::int64_t c) {
    const auto a = boost::add_edge(u, v, g).first, r = boost::add_edge(v, u, g).first;
    boost::put(boost::edge_capacity, g, a, c), boost::put(boost::edge_capacity, g, r, 0);
    boost::put(boost::edge_reverse, g, a, r), boost::put(boost::edge_reverse, g, r, a);
}

// Sums stay within int64 with room for the algorithm's excesses.
constexpr std::int64_t kMaxTotal = std::int64_t(1) << 61;

void checkNode(std::int64_t n, std::int64_t nodes) {
    if (n < 0 || n >= nodes)
        throw std::invalid_argument("maxFlow: node " + std::to_string(n) + " is not in 0.." + std::to_string(nodes - 1));
}
}  // namespace

std::int64_t maxFlow(std::int64_t nodes, const std::vector<std::int64_t>& n1, const std::vector<std::int64_t>& n2,
                     const std::vector<std::int64_t>& capacity, const std::vector<std::int64_t>& sources,
                     const std::vector<std::int64_t>& sinks) {
    if (n1.size() != n2.size() || n1.size() != capacity.size())
        throw std::invalid_argument("maxFlow: n1, n2 and capacity differ in length");
    std::vector<bool> isSource(nodes, false);
    for (std::int64_t s : sources) checkNode(s, nodes), isSource[s] = true;
    for (std::int64_t s : sinks) {
        checkNode(s, nodes);
        if (isSource[s]) throw std::invalid_argument("maxFlow: node " + std::to_string(s) + " is a source and a sink");
    }
    // Each node's capacity: the sum over its edges, all a flow can pass through it.
    std::vector<std::int64_t> through(nodes, 0);
    std::int64_t total = 0;
    for (std::size_t e = 0; e < capacity.size(); ++e) {
        checkNode(n1[e], nodes), checkNode(n2[e], nodes);
        if (capacity[e] < 0) throw std::invalid_argument("maxFlow: a negative capacity");
        if (capacity[e] > kMaxTotal - total) throw std::invalid_argument("maxFlow: the capacities sum above 2^61");
        total += capacity[e], through[n1[e]] += capacity[e], through[n2[e]] += capacity[e];
    }
    const std::int64_t source = nodes, sink = nodes + 1;
    Graph g(nodes + 2);
    for (std::size_t e = 0; e < capacity.size(); ++e)
        if (capacity[e] > 0) addArc(g, n1[e], n2[e], capacity[e]), addArc(g, n2[e], n1[e], capacity[e]);
    // A source or sink s joins the super-node by its own capacity: no flow
    // through s can exceed it, so the maximum flow is that with no bound there,
    // and the excesses the algorithm starts from sum to at most 2 x total.
    for (std::int64_t s : sources) addArc(g, source, s, through[s]);
    for (std::int64_t s : sinks) addArc(g, s, sink, through[s]);
    return boost::push_relabel_max_flow(g, source, sink);
}

}  // namespace ldem
