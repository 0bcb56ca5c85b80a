// Self-collision, an iteration's contacts (cpu_self_collision.cpp correct, visitOwners,
// pointAgainstTriangles, addContact): each vertex p visits its 27 cells, takes each owner q > p
// of exactly the cell visited, and corrects the contacts between their elements; corrections are
// summed in fixed point with integer atomics (the same sum in any order).
#include "layout.glsl"
#include "common.glsl"
#include "self_contact.glsl"

layout(local_size_x = 256) in;

int gContacts = 0;

vec3 yOf(uint k) { return selfVector(k, kSelfY); }
vec3 refOf(uint k) { return selfVector(k, kSelfRef); }

void addContact(ContactGeometry g, uint v[4]) {
    if (!(g.gap < uThickness * 0.99)) return;  // kSlack
    vec4 w;
    vec3 slip = vec3(0.0);
    for (int j = 0; j < 4; ++j) {
        w[j] = positions[v[j]].w;  // 1/m, 0 pinned
        slip += g.alpha[j] * (yOf(v[j]) - selfVector(v[j], kSelfZ));
    }
    vec3 change;
    float weight;
    if (!contactChange(g, w, slip, change, weight)) return;
    ++gContacts;
    float limit = 4.0 * uThickness;
    for (int j = 0; j < 4; ++j) {
        vec3 dx = (g.alpha[j] * w[j] / weight) * change;
        uint at = selfSums() + 4u * v[j];
        for (int c = 0; c < 3; ++c)
            atomicAdd(selfInts[at + uint(c)], int(round(clamp(dx[c], -limit, limit) * uFixedScale)));
        // The contact that takes a vertex past what its sums hold names it (the lowest).
        if (atomicAdd(selfInts[at + 3u], 1) == kSelfMostTouches)
            atomicMin(selfInts[8], int(v[j]));
    }
}

void pointAgainstTriangles(uint p, uint q) {
    int qi = int(q % uint(gridU())), qj = int(q / uint(gridU()));
    if (qi + 1 >= gridU() || qj + 1 >= gridV()) return;
    vec3 point = yOf(p), halfH = vec3(0.5 * uThickness);
    if (any(lessThan(point + halfH, selfVector(q, kSelfLow))) ||
        any(lessThan(selfVector(q, kSelfHigh) + halfH, point)))
        return;
    for (int t = 0; t < 2; ++t) {
        uint v[4];
        v[0] = p;
        for (int c = 0; c < 3; ++c) v[c + 1] = vertexIndex(ivec2(qi, qj) + kOwnedTriangles[3 * t + c]);
        if (p == v[1] || p == v[2] || p == v[3]) continue;
        float side = pointTriangleSide(refOf(v[0]), refOf(v[1]), refOf(v[2]), refOf(v[3]));
        ContactGeometry g;
        if (pointTriangle(yOf(v[0]), yOf(v[1]), yOf(v[2]), yOf(v[3]), side, g) &&
            abs(g.gap) < uThickness)
            addContact(g, v);
    }
}

void visitOwners(uint p, uint q) {
    if (any(lessThan(selfVector(p, kSelfHigh), selfVector(q, kSelfLow))) ||
        any(lessThan(selfVector(q, kSelfHigh), selfVector(p, kSelfLow))))
        return;
    pointAgainstTriangles(p, q);
    pointAgainstTriangles(q, p);
    ivec2 pij = ivec2(int(p % uint(gridU())), int(p / uint(gridU())));
    ivec2 qij = ivec2(int(q % uint(gridU())), int(q / uint(gridU())));
    for (int a = 0; a < 3; ++a) {
        ivec2 pe = pij + kOwnedEdgeEnds[a];
        if (pe.x >= gridU() || pe.y >= gridV()) continue;
        uint p1 = vertexIndex(pe);
        vec3 pa = yOf(p), pb = yOf(p1);
        for (int b = 0; b < 3; ++b) {
            ivec2 qe = qij + kOwnedEdgeEnds[b];
            if (qe.x >= gridU() || qe.y >= gridV()) continue;
            uint q1 = vertexIndex(qe);
            if (p1 == q || p1 == q1 || p == q1) continue;
            vec3 qa = yOf(q), qb = yOf(q1);
            if (any(lessThan(max(pa, pb) + uThickness, min(qa, qb))) ||
                any(lessThan(max(qa, qb) + uThickness, min(pa, pb))))
                continue;
            uint v[4] = uint[4](p, p1, q, q1);
            vec3 refCross = cross(refOf(p1) - refOf(p), refOf(q1) - refOf(q));
            float side = sideOf(dot(refCross, refOf(p) - refOf(q)));
            ContactGeometry g;
            if (edgeEdge(pa, pb, qa, qb, side, refCross, g) && abs(g.gap) < uThickness)
                addContact(g, v);
        }
    }
}

void main() {
    uint p = selfInvocation();
    if (p >= selfCount()) return;
    uint cells = selfCells();
    ivec3 home = ivec3(selfInts[cells + 4u * p], selfInts[cells + 4u * p + 1u],
                       selfInts[cells + 4u * p + 2u]);
    for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                ivec3 cell = home + ivec3(dx, dy, dz);
                uint b = hashCell(cell);
                int end = selfInts[selfStarts() + b + 1u];
                for (int s = selfInts[selfStarts() + b]; s < end; ++s) {
                    uint q = uint(selfInts[selfSorted() + uint(s)]);
                    // Buckets mix cells: only q's own cell counts, so no pair is seen twice.
                    if (p < q && selfInts[cells + 4u * q] == cell.x &&
                        selfInts[cells + 4u * q + 1u] == cell.y &&
                        selfInts[cells + 4u * q + 2u] == cell.z)
                        visitOwners(p, q);
                }
            }
    if (gContacts > 0) atomicAdd(selfInts[7], gContacts);
}
