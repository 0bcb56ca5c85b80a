// Checks of the self-intersection oracle (reference/self_intersection.h) on meshes whose answers
// are worked out by hand: interlocked triangles, an edge beside a shared side, each region of the
// closest point on a triangle, skew edges, a flat grid, a grid folded onto itself and the same
// fold pushed through, one wide triangle among small ones; the grid's answers against all-pairs
// ones on a crumpled fold; bad arguments. (Its OBJ reader: read_obj_test.cpp.)
#include "reference/self_intersection.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace cloth {
namespace {

using ref::TriangleMesh;
using V3 = std::array<double, 3>;

constexpr double kInfinity = std::numeric_limits<double>::infinity();

V3 sub(const V3& a, const V3& b) {
    return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
double dot(const V3& a, const V3& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
V3 cross(const V3& a, const V3& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double norm(const V3& a) {
    return std::sqrt(dot(a, a));
}

std::set<std::pair<int, int>> edgesOf(const TriangleMesh& m) {
    std::set<std::pair<int, int>> edges;
    for (const auto& t : m.triangles) {
        for (int k = 0; k < 3; ++k) {
            edges.insert({std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])});
        }
    }
    return edges;
}

// nx x ny vertices (index j*nx + i at (i, j, 0)*spacing), each cell split along its (i, j) to
// (i+1, j+1) diagonal.
TriangleMesh gridMesh(int nx, int ny, double spacing) {
    TriangleMesh m;
    for (int j = 0; j < ny; ++j) {
        for (int i = 0; i < nx; ++i) m.positions.push_back({i * spacing, j * spacing, 0.0});
    }
    for (int j = 0; j + 1 < ny; ++j) {
        for (int i = 0; i + 1 < nx; ++i) {
            const int a = j * nx + i, b = a + 1, c = a + nx, d = c + 1;
            m.triangles.push_back({a, b, d});
            m.triangles.push_back({a, d, c});
        }
    }
    return m;
}

// A 9 x 5 grid of spacing 0.25 folded at column 4: column 4 + k lies at the place of column
// 4 - k, raised by `gap`. Column 5 sits two edges from the column 3 below it (through the fold),
// column 6 four edges from column 2, and so on.
TriangleMesh foldedGrid(double gap) {
    constexpr int nx = 9, ny = 5, fold = 4;
    TriangleMesh m = gridMesh(nx, ny, 0.25);
    for (int j = 0; j < ny; ++j) {
        for (int i = fold + 1; i < nx; ++i) {
            m.positions[j * nx + i] = m.positions[j * nx + 2 * fold - i];
            m.positions[j * nx + i][2] = gap;
        }
    }
    return m;
}

// Every (edge, triangle) pair without a shared vertex, solved for p + s(q - p) = a + u(b - a) +
// v(c - a) by Cramer's rule: a formulation unlike the oracle's signed volumes, for generic
// meshes where no crossing is borderline.
long bruteForceCrossings(const TriangleMesh& m) {
    auto det = [](const V3& a, const V3& b, const V3& c) { return dot(a, cross(b, c)); };
    long count = 0;
    for (const auto& [p, q] : edgesOf(m)) {
        for (const auto& t : m.triangles) {
            if (t[0] == p || t[1] == p || t[2] == p || t[0] == q || t[1] == q || t[2] == q)
                continue;
            const V3& a = m.positions[t[0]];
            const V3 d = sub(m.positions[q], m.positions[p]), r = sub(a, m.positions[p]);
            const V3 e1 = sub(a, m.positions[t[1]]), e2 = sub(a, m.positions[t[2]]);
            const double D = det(d, e1, e2);  // d s + e1 u + e2 v = r, the e's negated
            if (D == 0) continue;
            const double s = det(r, e1, e2) / D, u = det(d, r, e2) / D, v = det(d, e1, r) / D;
            if (s > 0 && s < 1 && u > 0 && v > 0 && u + v < 1) ++count;
        }
    }
    return count;
}

// All pairs, the ring test from a breadth-first search per vertex, and distances by other
// formulas than the oracle's: the foot of the perpendicular on the plane when it falls inside
// the triangle, else the nearest side; the length of the segments' common perpendicular when it
// joins their interiors, else the nearest end.
double bruteForceSeparation(const TriangleMesh& m, int rings) {
    const int n = static_cast<int>(m.positions.size());
    const auto edges = edgesOf(m);
    std::vector<std::vector<int>> adjacent(n), hops(n, std::vector<int>(n, n + 1));
    for (const auto& [a, b] : edges) adjacent[a].push_back(b), adjacent[b].push_back(a);
    for (int s = 0; s < n; ++s) {
        std::vector<int> queue{s};
        hops[s][s] = 0;
        for (size_t h = 0; h < queue.size(); ++h) {
            for (const int w : adjacent[queue[h]]) {
                if (hops[s][w] > n) hops[s][w] = hops[s][queue[h]] + 1, queue.push_back(w);
            }
        }
    }
    const auto& x = m.positions;
    auto pointSegment = [&](const V3& p, const V3& a, const V3& b) {
        const V3 ab = sub(b, a);
        const double t = std::clamp(dot(sub(p, a), ab) / dot(ab, ab), 0.0, 1.0);
        return norm(sub(p, {a[0] + t * ab[0], a[1] + t * ab[1], a[2] + t * ab[2]}));
    };
    double best = kInfinity;
    for (int v = 0; v < n; ++v) {
        for (const auto& t : m.triangles) {
            if (hops[v][t[0]] <= rings || hops[v][t[1]] <= rings || hops[v][t[2]] <= rings)
                continue;
            const V3 &a = x[t[0]], &b = x[t[1]], &c = x[t[2]], &p = x[v];
            const V3 normal = cross(sub(b, a), sub(c, a));
            const double h = dot(sub(p, a), normal) / dot(normal, normal);
            const V3 foot{p[0] - h * normal[0], p[1] - h * normal[1], p[2] - h * normal[2]};
            const bool inside = dot(cross(sub(b, a), sub(foot, a)), normal) >= 0 &&
                                dot(cross(sub(c, b), sub(foot, b)), normal) >= 0 &&
                                dot(cross(sub(a, c), sub(foot, c)), normal) >= 0;
            best = std::min(best, inside ? std::abs(h) * norm(normal)
                                         : std::min({pointSegment(p, a, b), pointSegment(p, b, c),
                                                     pointSegment(p, c, a)}));
        }
    }
    for (const auto& [a1, b1] : edges) {
        for (const auto& [a2, b2] : edges) {
            if (std::make_pair(a2, b2) <= std::make_pair(a1, b1) || hops[a1][a2] <= rings ||
                hops[a1][b2] <= rings || hops[b1][a2] <= rings || hops[b1][b2] <= rings) {
                continue;
            }
            const V3 d1 = sub(x[b1], x[a1]), d2 = sub(x[b2], x[a2]), w = sub(x[a2], x[a1]);
            const V3 normal = cross(d1, d2);
            const double nn = dot(normal, normal);
            const double s = dot(cross(w, d2), normal) / nn, t = dot(cross(w, d1), normal) / nn;
            best = std::min({best, pointSegment(x[a1], x[a2], x[b2]),
                             pointSegment(x[b1], x[a2], x[b2]), pointSegment(x[a2], x[a1], x[b1]),
                             pointSegment(x[b2], x[a1], x[b1])});
            if (nn > 0 && s > 0 && s < 1 && t > 0 && t < 1) {
                best = std::min(best, std::abs(dot(w, normal)) / std::sqrt(nn));
            }
        }
    }
    return best;
}

// Two triangles, one in z = 0 and one in y = 0.5, each with one edge through the other: the
// vertical edge (0.5, 0.5, -1)-(0.5, 0.5, 1) meets z = 0 at (0.5, 0.5) inside the first, and the
// first's side (2, 0, 0)-(0, 2, 0) meets y = 0.5 at x = 1.5, z = 0, inside the second. No other
// edge reaches the other triangle, so the count is 2.
TriangleMesh interlockedTriangles(double shiftX) {
    return {{{0, 0, 0},
             {2, 0, 0},
             {0, 2, 0},
             {0.5 + shiftX, 0.5, -1},
             {0.5 + shiftX, 0.5, 1},
             {5 + shiftX, 0.5, 0.1}},
            {{0, 1, 2}, {3, 4, 5}}};
}

TEST(SelfIntersection, InterlockedTrianglesCrossTwiceAndApartNotAtAll) {
    EXPECT_EQ(ref::countEdgeTriangleCrossings(interlockedTriangles(0)), 2);
    EXPECT_EQ(bruteForceCrossings(interlockedTriangles(0)), 2);
    EXPECT_EQ(ref::countEdgeTriangleCrossings(interlockedTriangles(10)), 0);
    // Touching is not crossing (the documented choice): a corner resting on the other's face.
    const TriangleMesh touching{
        {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0.5, 0.5, 0}, {0.5, 0.5, 1}, {5, 0.5, 1}},
        {{0, 1, 2}, {3, 4, 5}}};
    EXPECT_EQ(ref::countEdgeTriangleCrossings(touching), 0);
    EXPECT_EQ(ref::minimumSeparation(touching, 2, 1.0).distance, 0.0);
}

// The square [0, 4]^2 split along its diagonal, pierced by a triangle whose cut through z = 0
// runs from (1, y) to (3, y + 2), parallel to the diagonal: two of its edges cross the sheet,
// each through exactly one of the square's two triangles, even 1e-15 from their shared side. At
// y = 1 both only touch the diagonal, which lies in the piercing plane: 0 (the documented choice).
TEST(SelfIntersection, EdgesNearASharedSideCrossOneTriangleEach) {
    auto pierced = [](double y) {
        return TriangleMesh{
            {{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}, {1, y, -1}, {1, y, 1}, {4, y + 3, 0.5}},
            {{0, 1, 2}, {0, 2, 3}, {4, 5, 6}}};
    };
    EXPECT_EQ(ref::countEdgeTriangleCrossings(pierced(1.0)), 0);
    for (const double y : {1.0 + 1e-15, 1.0 - 1e-15, 0.5, 1.5}) {
        EXPECT_EQ(ref::countEdgeTriangleCrossings(pierced(y)), 2) << y;
        EXPECT_EQ(bruteForceCrossings(pierced(y)), 2) << y;
    }
}

TEST(SelfIntersection, StackedTrianglesAreTheirGapApart) {
    TriangleMesh m{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 0.5}, {1, 0, 0.5}, {0, 1, 0.5}},
                   {{0, 1, 2}, {3, 4, 5}}};
    const ref::Separation s = ref::minimumSeparation(m, 2, 1.0);
    EXPECT_DOUBLE_EQ(s.distance, 0.5);
    EXPECT_FALSE(s.pair.empty());
    EXPECT_EQ(ref::minimumSeparation(m, 2, 0.4).distance, kInfinity);  // beyond the cutoff
    m.triangles.pop_back();  // one triangle: every pair shares a vertex
    EXPECT_EQ(ref::minimumSeparation(m, 0, kInfinity).distance, kInfinity);
}

// A probe triangle, nearly a vertical ray up from its corner p (listed first, so that its
// (vertex, triangle) pair wins ties), over the triangle (0, 0, 0), (4, 0, 0), (0, 4, 0): p is
// 0.3 above the plane, over each of the seven regions of the closest-point walk in turn.
TEST(SelfIntersection, PointTriangleDistanceInEveryRegion) {
    const double h2 = 0.09;
    const std::vector<std::pair<V3, double>> cases{
        {{1, 0.5, 0.3}, std::sqrt(h2)},      // interior
        {{2, -1, 0.3}, std::sqrt(1 + h2)},   // side along x
        {{-1, 2, 0.3}, std::sqrt(1 + h2)},   // side along y
        {{3, 3, 0.3}, std::sqrt(2 + h2)},    // the hypotenuse x + y = 4
        {{-1, -1, 0.3}, std::sqrt(2 + h2)},  // corner (0, 0)
        {{5, -1, 0.3}, std::sqrt(2 + h2)},   // corner (4, 0)
        {{-1, 5, 0.3}, std::sqrt(2 + h2)}};  // corner (0, 4)
    for (const auto& [p, expected] : cases) {
        const TriangleMesh m{
            {p, {p[0], p[1], 100}, {p[0] + 1, p[1], 100}, {0, 0, 0}, {4, 0, 0}, {0, 4, 0}},
            {{0, 1, 2}, {3, 4, 5}}};
        const ref::Separation s = ref::minimumSeparation(m, 2, 10.0);
        EXPECT_NEAR(s.distance, expected, 1e-12) << p[0] << " " << p[1];
        EXPECT_EQ(s.pair, "vertex 0 - triangle 1") << p[0] << " " << p[1];
    }
}

// Two triangles whose nearest parts are the middles of two skew edges: the x axis and the line
// x = 0, z = 0.3; every corner is at least sqrt(1.09) from the other triangle.
TEST(SelfIntersection, SkewEdgesMeetInTheirInteriors) {
    const TriangleMesh m{
        {{-1, 0, 0}, {1, 0, 0}, {0, 0, -1}, {0, -1, 0.3}, {0, 1, 0.3}, {0, 0, 1.3}},
        {{0, 1, 2}, {3, 4, 5}}};
    const ref::Separation s = ref::minimumSeparation(m, 2, 10.0);
    EXPECT_NEAR(s.distance, 0.3, 1e-12);
    EXPECT_EQ(s.pair, "edge 0-1 - edge 3-4");
    EXPECT_EQ(ref::countEdgeTriangleCrossings(m), 0);
}

// In the flat grid the nearest non-neighbours lie along the anti-diagonal (1, -1), the one
// direction without a mesh edge: a step of length sqrt(2) there costs two edges. With rings = 2
// vertex (0, 2) may not reach the triangle (1, 0), (2, 0), (2, 1) whose corners are 3, 4 and 3
// edges away, and its side from (1, 0) to (2, 1), the line x - y = 1, is 3/sqrt(2) from it; the
// edge (0, 2)-(0, 3) and the diagonal (1, 0)-(2, 1) tie. In general rings r gives (r+1)/sqrt(2).
TEST(SelfIntersection, FlatGridHasNoCrossingsAndKnownSeparation) {
    const TriangleMesh m = gridMesh(5, 5, 1.0);
    EXPECT_EQ(ref::countEdgeTriangleCrossings(m), 0);
    for (int rings = 0; rings <= 3; ++rings) {
        const double expected = (rings + 1) / std::sqrt(2.0);
        EXPECT_NEAR(ref::minimumSeparation(m, rings, 10.0).distance, expected, 1e-12) << rings;
        EXPECT_NEAR(ref::minimumSeparation(m, rings, kInfinity).distance, expected, 1e-12);
    }
    const ref::Separation s = ref::minimumSeparation(m, 2, 10.0);
    EXPECT_NE(s.pair.find("vertex"), std::string::npos) << s.pair;     // found first, ties kept
    EXPECT_EQ(ref::minimumSeparation(m, 2, 2.0).distance, kInfinity);  // 2.12 > cutoff
}

// The two layers are 0.01 apart everywhere; the only closer parts are the fold's own slanted
// triangles, within two edges of what lies below them. So rings = 2 reads the gap, and
// rings 0 and 1 see the fold's inside, which is closer.
TEST(SelfIntersection, FoldedGridReadsItsGap) {
    const TriangleMesh m = foldedGrid(0.01);
    EXPECT_EQ(ref::countEdgeTriangleCrossings(m), 0);
    const ref::Separation s = ref::minimumSeparation(m, 2, 0.05);
    EXPECT_NEAR(s.distance, 0.01, 1e-12) << s.pair;
    EXPECT_LT(ref::minimumSeparation(m, 1, 0.05).distance, 0.01 - 1e-6);
    EXPECT_LT(ref::minimumSeparation(m, 0, 0.05).distance, 0.01 - 1e-6);
}

// The top layer shifted by 0.3 spacing along y (so that nothing lines up with the layer below)
// and, beyond column 5, pushed down to z = -0.02. Columns 5-6 of the top cross z = 0 a third of
// the way along: 4 of their 5 sides along x and all 4 diagonals land over the bottom layer (8),
// and the bottom's 4 sides along x within the shifted strip and 4 diagonals cross the top's
// slanted band (8): 16.
TEST(SelfIntersection, FoldPushedThroughCrosses) {
    TriangleMesh m = foldedGrid(0.01);
    for (int j = 0; j < 5; ++j) {
        for (int i = 5; i < 9; ++i) {
            m.positions[j * 9 + i][1] += 0.075;
            if (i >= 6) m.positions[j * 9 + i][2] = -0.02;
        }
    }
    EXPECT_EQ(ref::countEdgeTriangleCrossings(m), 16);
    EXPECT_EQ(bruteForceCrossings(m), 16);
}

// A 16 x 16 fold with pseudo-random heights, so that the layers cross in places: the grid's
// answers must equal all-pairs ones for every ring count and cutoff.
TEST(SelfIntersection, GridAgreesWithAllPairsOnACrumpledFold) {
    constexpr int n = 16, fold = 8;
    TriangleMesh m = gridMesh(n, n, 1.0 / (n - 1));
    unsigned state = 12345;
    auto random = [&] {  // uniform in [-1, 1)
        state = state * 1664525u + 1013904223u;
        return (state >> 8) / double(1 << 23) - 1.0;
    };
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            V3& p = m.positions[j * n + i];
            if (i > fold) p = m.positions[j * n + 2 * fold - i], p[2] = 0.01;
            p[0] += 0.01 * random(), p[1] += 0.01 * random(), p[2] += 0.012 * random();
        }
    }
    const long crossings = ref::countEdgeTriangleCrossings(m);
    EXPECT_GT(crossings, 0);
    EXPECT_EQ(crossings, bruteForceCrossings(m));
    for (int rings = 0; rings <= 3; ++rings) {
        const double expected = bruteForceSeparation(m, rings);
        ASSERT_LT(expected, 0.05) << rings;
        const ref::Separation near = ref::minimumSeparation(m, rings, 0.05);
        EXPECT_NEAR(near.distance, expected, 1e-12) << rings;
        const ref::Separation all = ref::minimumSeparation(m, rings, kInfinity);
        EXPECT_EQ(all.distance, near.distance) << rings;
        EXPECT_EQ(all.pair, near.pair) << rings;
        EXPECT_EQ(ref::minimumSeparation(m, rings, 0.99 * expected).distance, kInfinity);
    }
}

// A 24 x 24 flat grid of spacing 1/23 and one large triangle standing across it in the plane
// y = 0.37, wider than the grid. Only the large one is filed as too wide for a cell, so only
// the list of wide boxes finds it. The grid's 24 edges along y and 23 diagonals between rows 8
// and 9 (y = 0.348 and 0.391) cross it, and row 9 is 9/23 - 0.37 = 0.0213 from it, closer than
// the grid's own non-neighbours (3 / sqrt(2) / 23 = 0.092).
TEST(SelfIntersection, OneWideTriangleAmongSmallOnes) {
    TriangleMesh m = gridMesh(24, 24, 1.0 / 23);
    const int first = static_cast<int>(m.positions.size());
    m.positions.insert(m.positions.end(), {{-1, 0.37, -1}, {2, 0.37, -1}, {0.5, 0.37, 1}});
    m.triangles.push_back({first, first + 1, first + 2});
    EXPECT_EQ(ref::countEdgeTriangleCrossings(m), 47);
    EXPECT_EQ(bruteForceCrossings(m), 47);
    const ref::Separation s = ref::minimumSeparation(m, 2, 0.05);
    EXPECT_NEAR(s.distance, 9.0 / 23 - 0.37, 1e-12) << s.pair;
    EXPECT_EQ(s.pair.substr(s.pair.find('-')), "- triangle 1058");
}

TEST(SelfIntersection, RejectsWhatItCannotMeasure) {
    TriangleMesh m = interlockedTriangles(0);
    EXPECT_THROW(ref::minimumSeparation(m, -1, 1.0), std::invalid_argument);
    EXPECT_THROW(ref::minimumSeparation(m, 2, -1.0), std::invalid_argument);
    EXPECT_THROW(ref::minimumSeparation(m, 2, std::nan("")), std::invalid_argument);
    m.positions[4][2] = std::nan("");
    EXPECT_THROW(ref::countEdgeTriangleCrossings(m), std::invalid_argument);
    EXPECT_THROW(ref::minimumSeparation(m, 2, 1.0), std::invalid_argument);
    m = interlockedTriangles(0);
    m.triangles.push_back({0, 1, 6});
    EXPECT_THROW(ref::countEdgeTriangleCrossings(m), std::invalid_argument);
    EXPECT_THROW(ref::minimumSeparation(m, 2, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace cloth
