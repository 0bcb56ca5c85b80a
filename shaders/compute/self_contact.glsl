// Self-collision on the GPU (docs/physics.md "Self-collision"): the buffers of its passes and
// the contact geometry, mirroring src/model/self_contact.h function for function, and the
// steps of src/cpu/cpu_self_collision.cpp one kernel each (self_*.comp). Included after
// layout.glsl and common.glsl.

// Six vec4 per vertex at 6k + slot, then x₀ of every vertex at 6N + k (kSelfStart: one copy
// of the positions fills it).
const uint kSelfY = 0u;      // the positions being corrected [m]
const uint kSelfRef = 1u;    // where the substep's motion took them: the contacts' sides
const uint kSelfZ = 2u;      // the substep's start: the slip friction acts on
const uint kSelfStep = 3u;   // the step's motion x₁ − x₀ [m]
const uint kSelfLow = 4u;    // the owner's box (its quad's corners), grown by h/2
const uint kSelfHigh = 5u;
const uint kSelfStart = 6u;  // x₀, the step's start
layout(std430, binding = 15) buffer SelfVectors {
    vec4 selfVectors[];
};
// The integers: a header, then per vertex its cell (xyz, bucket), the vertices sorted by
// bucket, the corrections summed in fixed point (xyz, contacts), the in-contact flags, then the
// hash's bucket starts (B + 1), cursors (B) and the scan's block sums. selfOffsets() gives them.
layout(std430, binding = 16) buffer SelfInts {
    int selfInts[];
};
// Header: [0..2] the motions' lower corner and [3..5] upper corner as ordered uints
// (orderedBits), [6] the longest owned edge's squared length (float bits), [7] the contacts of
// the iteration, [8] its lowest vertex in more than kSelfMostTouches contacts (INT_MAX: none).
const uint kSelfHeader = 16u;
// The contacts one vertex's fixed-point sums hold (model/self_contact.h kSelfMostTouches).
const int kSelfMostTouches = 64;

layout(location = 20) uniform float uThickness;  // h [m]
layout(location = 21) uniform float uFriction;   // μ
layout(location = 22) uniform float uFixedScale; // fixed-point units per metre
layout(location = 23) uniform float uShare;      // 1 / the step's substeps

const uint kScanBlock = 256u;  // the work group of the passes over vertices and of the scan

uint selfCount() { return uint(gridU()) * uint(gridV()); }
// Buckets: the smallest power of two at least twice the vertices (as the CPU's table).
uint selfBuckets() { return 1u << uint(findMSB(2u * selfCount() - 1u) + 1); }
uint selfCells() { return kSelfHeader; }
uint selfSorted() { return selfCells() + 4u * selfCount(); }
uint selfSums() { return selfSorted() + selfCount(); }
uint selfFlags() { return selfSums() + 4u * selfCount(); }
uint selfStarts() { return selfFlags() + selfCount(); }
uint selfCursors() { return selfStarts() + selfBuckets() + 1u; }
uint selfBlockSums() { return selfCursors() + selfBuckets(); }

uint selfVectorAt(uint k, uint slot) {
    return slot == kSelfStart ? 6u * selfCount() + k : 6u * k + slot;
}
vec3 selfVector(uint k, uint slot) { return selfVectors[selfVectorAt(k, slot)].xyz; }
void setSelfVector(uint k, uint slot, vec3 v) { selfVectors[selfVectorAt(k, slot)] = vec4(v, 0.0); }

// The invocation's index in a 1-D pass of work groups of kScanBlock, laid out in 2-D when the
// groups pass 65535 (DESIGN.md §3).
uint selfInvocation() {
    return (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * kScanBlock +
           gl_LocalInvocationID.x;
}

// A float's bits as a uint that orders as the float does (for atomicMin/atomicMax).
uint orderedBits(float x) {
    uint b = floatBitsToUint(x);
    return (b & 0x80000000u) != 0u ? ~b : b | 0x80000000u;
}
float fromOrderedBits(uint b) {
    return uintBitsToFloat((b & 0x80000000u) != 0u ? b & 0x7fffffffu : ~b);
}

// Teschner et al. 2003, as the CPU's hashCell.
uint hashCell(ivec3 c) {
    return ((uint(c.x) * 73856093u) ^ (uint(c.y) * 19349663u) ^ (uint(c.z) * 83492791u)) &
           (selfBuckets() - 1u);
}

// The triangles and edges vertex (i, j) owns (model/self_contact.h kOwnedTriangles,
// kOwnedEdgeEnds).
const ivec2 kOwnedTriangles[6] =
    ivec2[6](ivec2(0, 0), ivec2(1, 0), ivec2(1, 1), ivec2(0, 0), ivec2(1, 1), ivec2(0, 1));
const ivec2 kOwnedEdgeEnds[3] = ivec2[3](ivec2(1, 0), ivec2(0, 1), ivec2(1, 1));

float sideOf(float x) { return x < 0.0 ? -1.0 : 1.0; }

struct ContactGeometry {
    vec4 alpha;
    vec3 normal;
    float gap;
};

float pointTriangleSide(vec3 p, vec3 a, vec3 b, vec3 c) {
    return sideOf(dot(cross(b - a, c - a), p - a));
}

bool pointTriangle(vec3 p, vec3 a, vec3 b, vec3 c, float side, out ContactGeometry g) {
    g.alpha = vec4(0.0);
    g.normal = vec3(0.0);
    g.gap = 0.0;
    vec3 e0 = b - a, e1 = c - a, ap = p - a;
    vec3 n = cross(e0, e1);
    float n2 = dot(n, n);
    if (!(n2 > 0.0)) return false;
    float d00 = dot(e0, e0), d01 = dot(e0, e1), d11 = dot(e1, e1);
    float d20 = dot(ap, e0), d21 = dot(ap, e1);
    float denominator = d00 * d11 - d01 * d01;
    if (!(denominator > 0.0)) return false;
    float v = (d11 * d20 - d01 * d21) / denominator, w = (d00 * d21 - d01 * d20) / denominator;
    float u = 1.0 - v - w;
    if (u >= 0.0 && v >= 0.0 && w >= 0.0) {
        g.normal = side * n / sqrt(n2);
        g.gap = dot(ap, g.normal);
        g.alpha = vec4(1.0, -u, -v, -w);
        return true;
    }
    float best = 3.0e38;
    vec3 corner[3] = vec3[3](a, b, c);
    for (int e = 0; e < 3; ++e) {
        vec3 s0 = corner[e], s1 = corner[(e + 1) % 3], d = s1 - s0;
        float t = clamp(dot(p - s0, d) / dot(d, d), 0.0, 1.0);
        vec3 r = p - (s0 + t * d);
        float r2 = dot(r, r);
        if (!(r2 < best)) continue;
        best = r2;
        vec3 weights = vec3(0.0);
        weights[e] = 1.0 - t;
        weights[(e + 1) % 3] = t;
        u = weights.x;
        v = weights.y;
        w = weights.z;
    }
    float distance = sqrt(best);
    if (!(distance > 0.0)) return false;
    vec3 closest = u * a + v * b + w * c;
    g.normal = (p - closest) / distance;
    g.gap = distance;
    g.alpha = vec4(1.0, -u, -v, -w);
    return true;
}

bool edgeEdge(vec3 p0, vec3 p1, vec3 q0, vec3 q1, float side, vec3 refCross,
              out ContactGeometry g) {
    g.alpha = vec4(0.0);
    g.normal = vec3(0.0);
    g.gap = 0.0;
    vec3 ep = p1 - p0, eq = q1 - q0, w0 = p0 - q0;
    float a = dot(ep, ep), b = dot(ep, eq), c = dot(eq, eq);
    float d = dot(ep, w0), e = dot(eq, w0);
    float denominator = a * c - b * b;
    if (!(denominator > 1e-6 * a * c)) return false;
    float s = (b * e - c * d) / denominator, t = (a * e - b * d) / denominator;
    if (!(s > 0.0 && s < 1.0 && t > 0.0 && t < 1.0)) return false;
    vec3 n = normalize(cross(ep, eq));
    if (dot(n, refCross) < 0.0) n = -n;
    g.normal = side * n;
    g.gap = dot(w0 + s * ep - t * eq, g.normal);
    g.alpha = vec4(1.0 - s, s, t - 1.0, -t);
    return true;
}

// model/self_contact.h contactCorrection, the change D it returns through `change` and the
// weight Σ α² w; false when nothing can move.
bool contactChange(ContactGeometry g, vec4 inverseMass, vec3 slip, out vec3 change,
                   out float weight) {
    weight = dot(g.alpha * g.alpha, inverseMass);
    change = vec3(0.0);
    if (!(weight > 0.0)) return false;
    float depth = uThickness - g.gap;
    change = depth * g.normal;
    if (uFriction > 0.0) {
        vec3 tangential = slip - dot(slip, g.normal) * g.normal;
        float length2 = dot(tangential, tangential);
        if (length2 > 0.0)
            change -= min(1.0, uFriction * depth / sqrt(length2)) * tangential;
    }
    return true;
}
