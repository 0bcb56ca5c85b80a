// See self_intersection.h. Every query runs over a uniform grid of cells holding element boxes:
// an element looks only at the elements filed in the cells its own box touches, so a frame
// costs about (elements x neighbours per cell) rather than elements squared.
#include "reference/self_intersection.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

namespace ref {
// Everything below has internal linkage: reference.h already has a ref::Box and a ref::V3, and
// this file must not clash with any other file of the test binary.
namespace {

using V3 = std::array<double, 3>;
using Edge = std::array<int, 2>;  // vertex indices, [0] < [1]

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
V3 along(const V3& a, double t, const V3& d) {  // a + t d
    return {a[0] + t * d[0], a[1] + t * d[1], a[2] + t * d[2]};
}
double distance(const V3& a, const V3& b) {
    const V3 d = sub(a, b);
    return std::sqrt(dot(d, d));
}

// ---- geometry ----------------------------------------------------------------------------------

double orient(const V3& a, const V3& b, const V3& c, const V3& d) {  // 6 x signed volume abcd
    return dot(sub(b, a), cross(sub(c, a), sub(d, a)));
}

// The segment of edge (p, q) passes through triangle t at one point of its interior. Any zero
// determinant means touching and is not counted. The side test of the line pq against a
// triangle side is evaluated with the side's vertices in index order and negated as needed, so
// two triangles sharing that side get exactly opposite values: a line crossing near the shared
// side passes inside exactly one of them, and no real crossing slips between the two.
bool properCrossing(const std::vector<V3>& x, int p, int q, const std::array<int, 3>& t) {
    const double sp = orient(x[t[0]], x[t[1]], x[t[2]], x[p]);
    const double sq = orient(x[t[0]], x[t[1]], x[t[2]], x[q]);
    if (!((sp > 0 && sq < 0) || (sp < 0 && sq > 0))) return false;
    auto side = [&](int u, int v) {
        return u < v ? orient(x[p], x[q], x[u], x[v]) : -orient(x[p], x[q], x[v], x[u]);
    };
    const double s0 = side(t[0], t[1]), s1 = side(t[1], t[2]), s2 = side(t[2], t[0]);
    return (s0 > 0 && s1 > 0 && s2 > 0) || (s0 < 0 && s1 < 0 && s2 < 0);
}

double pointSegmentDistance(const V3& p, const V3& a, const V3& b) {
    const V3 ab = sub(b, a);
    const double length2 = dot(ab, ab);
    const double t = length2 > 0 ? std::clamp(dot(sub(p, a), ab) / length2, 0.0, 1.0) : 0.0;
    return distance(p, along(a, t, ab));
}

// Ericson's Voronoi-region walk (Real-Time Collision Detection §5.1.5): the closest point is a
// corner, a point of a side, or the projection into the interior. A triangle without area has
// no interior, and the walk would divide by zero, so its sides answer instead.
double pointTriangleDistance(const V3& p, const V3& a, const V3& b, const V3& c) {
    const V3 ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
    const V3 n = cross(ab, ac);
    if (dot(n, n) == 0) {
        return std::min({pointSegmentDistance(p, a, b), pointSegmentDistance(p, b, c),
                         pointSegmentDistance(p, c, a)});
    }
    const double d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) return distance(p, a);
    const V3 bp = sub(p, b);
    const double d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) return distance(p, b);
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return distance(p, along(a, d1 / (d1 - d3), ab));
    const V3 cp = sub(p, c);
    const double d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return distance(p, c);
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return distance(p, along(a, d2 / (d2 - d6), ac));
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
        return distance(p, along(b, (d4 - d3) / ((d4 - d3) + (d5 - d6)), sub(c, b)));
    }
    const double sum = va + vb + vc;
    return distance(p, along(along(a, vb / sum, ab), vc / sum, ac));
}

// The closest pair of two segments either has an end of one of them or is the pair of interior
// points where the lines' common perpendicular lands inside both. Each candidate is the
// distance of an actual pair of points, so the minimum never undershoots; for (near-)parallel
// segments, where the interior solve is lost, the ends are within L*angle/2 of the truth.
double segmentSegmentDistance(const V3& p1, const V3& q1, const V3& p2, const V3& q2) {
    double best = std::min({pointSegmentDistance(p1, p2, q2), pointSegmentDistance(q1, p2, q2),
                            pointSegmentDistance(p2, p1, q1), pointSegmentDistance(q2, p1, q1)});
    const V3 d1 = sub(q1, p1), d2 = sub(q2, p2), r = sub(p1, p2);
    const double a = dot(d1, d1), b = dot(d1, d2), c = dot(d1, r), e = dot(d2, d2), f = dot(d2, r);
    const double denominator = a * e - b * b;  // |d1 x d2|^2
    if (denominator > 0) {
        const double s = (b * f - c * e) / denominator, t = (a * f - b * c) / denominator;
        if (s > 0 && s < 1 && t > 0 && t < 1) {
            best = std::min(best, distance(along(p1, s, d1), along(p2, t, d2)));
        }
    }
    return best;
}

// ---- the grid ----------------------------------------------------------------------------------

struct Bounds {
    V3 lo, hi;
};

template <size_t N>
Bounds boundsOf(const std::vector<V3>& x, const std::array<int, N>& ids) {
    Bounds b{x[ids[0]], x[ids[0]]};
    for (const int i : ids) {
        for (int k = 0; k < 3; ++k) {
            b.lo[k] = std::min(b.lo[k], x[i][k]);
            b.hi[k] = std::max(b.hi[k], x[i][k]);
        }
    }
    return b;
}

bool overlap(const Bounds& a, const Bounds& b) {
    for (int k = 0; k < 3; ++k) {
        if (a.lo[k] > b.hi[k] || b.lo[k] > a.hi[k]) return false;
    }
    return true;
}

double widthOf(const Bounds& b) {
    return std::max({b.hi[0] - b.lo[0], b.hi[1] - b.lo[1], b.hi[2] - b.lo[2]});
}

// Cubic cells over the stored boxes, each box filed once, in the cell of its low corner, as rows
// of a dense array (x fastest, so that a run of cells along x is one stretch of memory). Cells
// are as wide as all but a thousandth of the boxes; the wider ones go to a list that every query
// scans. A small box whose low corner lies more than a cell below a query's cannot reach it, so
// a query looks 1.5 cells further down (the half for rounding) and not at all further up.
// Coordinates clamp to the grid: clamping is monotone, so it loses no pair, and a query grown by
// an infinite cutoff simply covers every cell.
class CellGrid {
public:
    explicit CellGrid(const std::vector<Bounds>& boxes) : lo_(boxes[0].lo) {
        V3 hi = boxes[0].hi;
        std::vector<double> widths;
        for (const Bounds& b : boxes) {
            widths.push_back(widthOf(b));
            for (int k = 0; k < 3; ++k) lo_[k] = std::min(lo_[k], b.lo[k]);
            for (int k = 0; k < 3; ++k) hi[k] = std::max(hi[k], b.hi[k]);
        }
        const size_t q = widths.size() - 1 - widths.size() / 1000;
        std::nth_element(widths.begin(), widths.begin() + q, widths.end());
        const double extent = std::max({hi[0] - lo_[0], hi[1] - lo_[1], hi[2] - lo_[2]});
        cell_ = std::max(widths[q], 1e-6 * extent);
        if (!(cell_ > 0)) cell_ = 1;  // every box one and the same point
        for (;; cell_ *= 1.25) {      // no more than a few cells per box, however spread out
            double cells = 1;
            for (int k = 0; k < 3; ++k) {
                count_[k] = static_cast<int64_t>((hi[k] - lo_[k]) / cell_) + 1;
                cells *= static_cast<double>(count_[k]);
            }
            if (cells <= 4.0 * boxes.size() + 64) break;
        }
        std::vector<int64_t> cellOfBox(boxes.size(), -1);
        starts_.assign(count_[0] * count_[1] * count_[2] + 1, 0);
        for (size_t id = 0; id < boxes.size(); ++id) {
            if (widthOf(boxes[id]) > cell_) {
                wide_.push_back({boxes[id], static_cast<int>(id)});
            } else {
                cellOfBox[id] = index(boxes[id].lo);
                ++starts_[cellOfBox[id] + 1];
            }
        }
        for (size_t c = 1; c < starts_.size(); ++c) starts_[c] += starts_[c - 1];
        entries_.resize(starts_.back());
        std::vector<int64_t> fill(starts_.begin(), starts_.end() - 1);
        for (size_t id = 0; id < boxes.size(); ++id) {
            if (cellOfBox[id] >= 0) entries_[fill[cellOfBox[id]]++] = {boxes[id], int(id)};
        }
    }

    // Calls f(id) once for every stored box that comes within `reach` of `box` on every axis.
    template <class F>
    void forEachNear(const Bounds& box, double reach, F f) const {
        Bounds grown = box;
        for (int k = 0; k < 3; ++k) grown.lo[k] -= reach, grown.hi[k] += reach;
        std::array<int64_t, 3> from, to;
        for (int k = 0; k < 3; ++k) {
            from[k] = cellOf(grown.lo[k] - 1.5 * cell_, k);
            to[k] = cellOf(grown.hi[k], k);
        }
        auto visit = [&](const Entry& e) {
            if (overlap(grown, e.box)) f(e.id);
        };
        for (int64_t z = from[2]; z <= to[2]; ++z) {
            for (int64_t y = from[1]; y <= to[1]; ++y) {
                const int64_t row = (z * count_[1] + y) * count_[0];
                const int64_t end = starts_[row + to[0] + 1];
                for (int64_t i = starts_[row + from[0]]; i < end; ++i) visit(entries_[i]);
            }
        }
        for (const Entry& e : wide_) visit(e);
    }

private:
    struct Entry {
        Bounds box;
        int id;
    };

    int64_t cellOf(double v, int k) const {
        const double c = std::floor((v - lo_[k]) / cell_);
        if (!(c > 0)) return 0;
        return c < static_cast<double>(count_[k] - 1) ? static_cast<int64_t>(c) : count_[k] - 1;
    }
    int64_t index(const V3& p) const {
        return (cellOf(p[2], 2) * count_[1] + cellOf(p[1], 1)) * count_[0] + cellOf(p[0], 0);
    }

    V3 lo_;
    double cell_;
    std::array<int64_t, 3> count_{1, 1, 1};
    std::vector<int64_t> starts_;  // cell c's boxes: entries_[starts_[c] .. starts_[c + 1])
    std::vector<Entry> entries_, wide_;
};

// ---- topology ----------------------------------------------------------------------------------

struct Topology {
    std::vector<Edge> edges;          // unique, sorted
    std::vector<int> firstNeighbour;  // vertex v's neighbours: neighbours[first[v]..first[v+1])
    std::vector<int> neighbours;
    std::vector<int> usedVertices;  // those of some triangle, ascending
};

Topology topologyOf(const TriangleMesh& mesh) {
    const int n = static_cast<int>(mesh.positions.size());
    for (const V3& p : mesh.positions) {
        if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
            throw std::invalid_argument("self-intersection check: non-finite vertex position");
        }
    }
    Topology topo;
    std::vector<char> used(n, 0);
    for (const auto& t : mesh.triangles) {
        for (int k = 0; k < 3; ++k) {
            if (t[k] < 0 || t[k] >= n) {
                throw std::invalid_argument("self-intersection check: triangle vertex " +
                                            std::to_string(t[k]) + " out of range");
            }
            used[t[k]] = 1;
            const int a = std::min(t[k], t[(k + 1) % 3]), b = std::max(t[k], t[(k + 1) % 3]);
            if (a != b) topo.edges.push_back({a, b});  // a repeated corner makes no edge
        }
    }
    std::sort(topo.edges.begin(), topo.edges.end());
    topo.edges.erase(std::unique(topo.edges.begin(), topo.edges.end()), topo.edges.end());
    topo.firstNeighbour.assign(n + 1, 0);
    for (const Edge& e : topo.edges)
        ++topo.firstNeighbour[e[0] + 1], ++topo.firstNeighbour[e[1] + 1];
    for (int v = 0; v < n; ++v) topo.firstNeighbour[v + 1] += topo.firstNeighbour[v];
    topo.neighbours.resize(topo.firstNeighbour[n]);
    std::vector<int> fill(topo.firstNeighbour.begin(), topo.firstNeighbour.end() - 1);
    for (const Edge& e : topo.edges) {
        topo.neighbours[fill[e[0]]++] = e[1];
        topo.neighbours[fill[e[1]]++] = e[0];
    }
    for (int v = 0; v < n; ++v) {
        if (used[v]) topo.usedVertices.push_back(v);
    }
    return topo;
}

}  // namespace

long countEdgeTriangleCrossings(const TriangleMesh& mesh) {
    const Topology topo = topologyOf(mesh);
    const std::vector<V3>& x = mesh.positions;
    const auto& triangles = mesh.triangles;
    if (triangles.empty()) return 0;
    std::vector<Bounds> boxes;
    for (const auto& t : triangles) boxes.push_back(boundsOf(x, t));
    const CellGrid grid(boxes);
    long crossings = 0;
    for (const Edge& edge : topo.edges) {
        const int p = edge[0], q = edge[1];  // named copies: lambdas may not capture bindings
        grid.forEachNear(boundsOf(x, edge), 0.0, [&](int t) {
            const auto& tri = triangles[t];
            const bool shared = tri[0] == p || tri[1] == p || tri[2] == p || tri[0] == q ||
                                tri[1] == q || tri[2] == q;
            if (!shared && properCrossing(x, p, q, tri)) ++crossings;
        });
    }
    return crossings;
}

Separation minimumSeparation(const TriangleMesh& mesh, int rings, double cutoff) {
    if (rings < 0) throw std::invalid_argument("minimumSeparation: rings must be >= 0");
    if (!(cutoff >= 0)) throw std::invalid_argument("minimumSeparation: cutoff must be >= 0");
    const Topology topo = topologyOf(mesh);
    const std::vector<V3>& x = mesh.positions;
    const auto& triangles = mesh.triangles;
    if (triangles.empty()) return {kInfinity, ""};

    // Marks the vertices within `rings` edges of the given ones (a breadth-first search from
    // all of them at once), with a fresh stamp so that marks need no clearing between elements.
    std::vector<int> mark(x.size(), -1), depth(x.size(), 0), queue;
    int stamp = 0;
    auto markNear = [&](const int* vertices, int count) {
        ++stamp;
        queue.clear();
        for (int i = 0; i < count; ++i) {
            if (mark[vertices[i]] != stamp) mark[vertices[i]] = stamp, queue.push_back(vertices[i]);
            depth[vertices[i]] = 0;
        }
        for (size_t head = 0; head < queue.size(); ++head) {
            const int u = queue[head];
            if (depth[u] == rings) continue;
            for (int i = topo.firstNeighbour[u]; i < topo.firstNeighbour[u + 1]; ++i) {
                const int w = topo.neighbours[i];
                if (mark[w] != stamp) mark[w] = stamp, depth[w] = depth[u] + 1, queue.push_back(w);
            }
        }
    };
    auto marked = [&](int v) { return mark[v] == stamp; };

    double best = kInfinity;
    std::string pair;
    auto offer = [&](double d, auto describe) {
        if (d <= cutoff && d < best) best = d, pair = describe();
    };
    // Two elements within distance d have boxes within d on every axis, so a query need reach
    // no further than the cutoff or the best pair so far (a pair only wins by being closer,
    // which keeps the reported pair the same as in a full scan); 1e-12 of the coordinates' size
    // covers rounding in the box arithmetic.
    double size = 0;
    for (const V3& p : x) size = std::max({size, std::abs(p[0]), std::abs(p[1]), std::abs(p[2])});
    auto reach = [&] { return std::min(best, cutoff) + 1e-12 * size; };

    // Vertex against triangle.
    std::vector<Bounds> triangleBoxes;
    for (const auto& t : triangles) triangleBoxes.push_back(boundsOf(x, t));
    const CellGrid triangleGrid(triangleBoxes);
    for (const int v : topo.usedVertices) {
        markNear(&v, 1);
        triangleGrid.forEachNear(boundsOf(x, std::array<int, 1>{v}), reach(), [&](int t) {
            const auto& tri = triangles[t];
            if (marked(tri[0]) || marked(tri[1]) || marked(tri[2])) return;
            offer(pointTriangleDistance(x[v], x[tri[0]], x[tri[1]], x[tri[2]]), [&] {
                return "vertex " + std::to_string(v) + " - triangle " + std::to_string(t);
            });
        });
    }

    // Edge against edge, each unordered pair once (the second edge's index is the larger).
    const std::vector<Edge>& edges = topo.edges;
    std::vector<Bounds> edgeBoxes;
    for (const Edge& e : edges) edgeBoxes.push_back(boundsOf(x, e));
    const CellGrid edgeGrid(edgeBoxes);
    auto name = [&](int e) {
        return "edge " + std::to_string(edges[e][0]) + "-" + std::to_string(edges[e][1]);
    };
    for (int e = 0; e < static_cast<int>(edges.size()); ++e) {
        markNear(edges[e].data(), 2);
        edgeGrid.forEachNear(edgeBoxes[e], reach(), [&](int f) {
            if (f <= e || marked(edges[f][0]) || marked(edges[f][1])) return;
            const double d = segmentSegmentDistance(x[edges[e][0]], x[edges[e][1]], x[edges[f][0]],
                                                    x[edges[f][1]]);
            offer(d, [&] { return name(e) + " - " + name(f); });
        });
    }
    return {best, pair};
}

}  // namespace ref
