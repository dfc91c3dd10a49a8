// The maximum flow (MaxFlow.hpp) on graphs whose minimum cut is known by hand.
#include <gtest/gtest.h>

#include <cstdint>
#include <stdexcept>
#include <vector>

#include "ldem/MaxFlow.hpp"

using namespace ldem;

// Two paths from 0 to 3, through 1 (capacities 5 then 2) and through 2 (4 then 7):
// the cheapest cut takes the 2 and the 4.
TEST(MaxFlow, TwoPathsCutAtTheirNarrowestEdges) {
    EXPECT_EQ(maxFlow(4, {0, 1, 0, 2}, {1, 3, 2, 3}, {5, 2, 4, 7}, {0}, {3}), 6);
}

// Edges are undirected: the same graph listed from the sink's side.
TEST(MaxFlow, EdgesCarryFlowEitherWay) {
    EXPECT_EQ(maxFlow(4, {1, 3, 2, 3}, {0, 1, 0, 2}, {5, 2, 4, 7}, {0}, {3}), 6);
}

// A flow that must run against the listing of the middle edge: 0-1 (3), 2-1 (3),
// 0-2 (1), 2-3 (4), and 1 hangs on nothing but 0 and 2, so all of 0-1 reaches 3 through 2.
TEST(MaxFlow, FlowThroughAnEdgeListedTheOtherWay) {
    EXPECT_EQ(maxFlow(4, {0, 2, 0, 2}, {1, 1, 2, 3}, {3, 3, 1, 4}, {0}, {3}), 4);
}

// Several sources and sinks; parallel edges add up; zero capacities carry nothing.
TEST(MaxFlow, SetsOfSourcesAndSinksAndParallelEdges) {
    // sources 0, 1; sinks 4, 5; 0-2 (3) twice, 1-2 (2), 2-3 (10), 3-4 (1), 3-5 (4), 1-5 (0)
    EXPECT_EQ(maxFlow(6, {0, 0, 1, 2, 3, 3, 1}, {2, 2, 2, 3, 4, 5, 5}, {3, 3, 2, 10, 1, 4, 0}, {0, 1}, {4, 5}), 5);
}

// Nothing joins the sets: no flow.
TEST(MaxFlow, DisconnectedSetsCarryNothing) {
    EXPECT_EQ(maxFlow(4, {0, 2}, {1, 3}, {9, 9}, {0}, {3}), 0);
}

// Large capacities stay exact in int64 (beyond int32 and double's 2^53).
TEST(MaxFlow, LargeCapacitiesAreExact) {
    const std::int64_t big = (std::int64_t(1) << 55) + 1;
    EXPECT_EQ(maxFlow(3, {0, 1}, {1, 2}, {big, big + 2}, {0}, {2}), big);
}

TEST(MaxFlow, RefusesBadInput) {
    EXPECT_THROW(maxFlow(2, {0}, {1}, {1}, {0}, {0}), std::invalid_argument);   // a node on both sides
    EXPECT_THROW(maxFlow(2, {0}, {2}, {1}, {0}, {1}), std::invalid_argument);   // a node out of range
    EXPECT_THROW(maxFlow(2, {0}, {1}, {-1}, {0}, {1}), std::invalid_argument);  // a negative capacity
    EXPECT_THROW(maxFlow(2, {0}, {1, 0}, {1}, {0}, {1}), std::invalid_argument);  // lengths differ
    const std::int64_t huge = std::int64_t(1) << 60;
    EXPECT_THROW(maxFlow(2, {0, 0, 0}, {1, 1, 1}, {huge, huge, huge}, {0}, {1}), std::invalid_argument);
}
