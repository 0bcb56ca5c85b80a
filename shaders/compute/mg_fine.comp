// implicit_euler's multigrid preconditioner: the fine grid's system A = m (1 + hc) I + h² H
// (+ h D) (+ h² K_grab at the grabbed vertex) as 25 blocks per vertex, in double, at the state of
// the right-hand side's pass (multigrid.glsl; src/cpu/cpu_multigrid.cpp probeFine reads the same
// blocks off the matrix-free product). With contacts in the solve, their normal springs on the
// diagonal. Per spring s of vertex k to q: −h² J_s − h βK d̂d̂ᵀ at q's
// offset, the same on the diagonal with the sign turned; the bending Hessian W ⊗ I, W_kq read off
// the bending stencil with a field that is 1 at q alone. Pinned vertices are constraints: their
// row and column are the identity's.
#include "layout.glsl"
#include "common.glsl"
#include "grab.glsl"
#include "springs.glsl"
#include "multigrid.glsl"
#include "solve_contact.glsl"
#ifdef HAS_BENDING
ivec2 gProbe;  // the vertex whose unit field the bending stencil reads
#define BENDING_FIELD(q) ((q) == gProbe ? vec3(1.0) : vec3(0.0))
#include "bending.glsl"
#endif

layout(local_size_x = WX, local_size_y = WY) in;

void addScaled(inout dmat3 b, double s, dvec3 n, double along, double transverse) {
    b += s * (dmat3(transverse) + along * outerProduct(n, n));
}

void main() {
    ivec2 ij;
    int k;
    if (!levelVertex(0, ij, k)) return;
    for (int o = 0; o < 25; ++o) storeBlock(blockAt(0, k, o), dmat3(0.0lf));
    float inverseMass = positions[k].w;
    if (inverseMass == 0.0) {
        storeBlock(blockAt(0, k, stencilSlot(0, 0)), dmat3(1.0lf));
        return;
    }
    double h = double(params.dt), h2 = h * h;
    float drag = 1.0 + params.dt * params.dampingRate;
    double m = divide(double(drag), double(inverseMass));
    dmat3 centre = dmat3(m);
    if (grabbed(uint(k))) centre += dmat3(h2 * double(uGrab.w));
#if NUM_SPRING_OFFSETS > 0
    dvec3 xk = dvec3(positions[k].xyz);
    for (int o = 0; o < NUM_SPRING_OFFSETS; ++o) {
        ivec4 s = kSpringOffsets[o];
        ivec2 q = ij + s.xy;
        if (!insideGrid(q)) continue;
        int kq = int(vertexIndex(q));
        dvec3 d = dvec3(positions[kq].xyz) - xk;
        double len = squareRoot(dot(d, d)), restLength = double(springRestLength(s));
        if (!(len >= 1e-12lf * restLength)) continue;
        dvec3 n = d * divide(1.0lf, len);
        double stiffness = double(springStiffnessAt(s, ij));
        double transverse = stiffness * max(0.0lf, 1.0lf - divide(restLength, len));
        double along = stiffness - transverse;
#ifdef HAS_SPRING_DAMPING
        along += divide(double(springDampingAt(s, ij)), h);
#endif
        addScaled(centre, h2, n, along, transverse);
        if (positions[kq].w == 0.0) continue;  // a pinned column
        int at = blockAt(0, k, stencilSlot(s.x, s.y));
        dmat3 b = loadBlock(at);
        addScaled(b, -h2, n, along, transverse);
        storeBlock(at, b);
    }
#endif
#ifdef HAS_BENDING
    for (int dj = -2; dj <= 2; ++dj)
        for (int di = -2; di <= 2; ++di) {
            gProbe = ij + ivec2(di, dj);
            if (!stencilReaches(0, di, dj) || !insideGrid(gProbe) ||
                positions[vertexIndex(gProbe)].w == 0.0)
                continue;
            double w = -double(bendingForce(ij, params.bending.xyz).x);
            if (w == 0.0lf) continue;
            if (di == 0 && dj == 0) {
                centre += dmat3(h2 * w);
                continue;
            }
            int at = blockAt(0, k, stencilSlot(di, dj));
            storeBlock(at, loadBlock(at) + dmat3(h2 * w));
        }
#endif
#ifdef HAS_SOLVE_CONTACTS
    // A contact in the solve as a stiff normal spring, 10 times the mean diagonal
    // (src/cpu/cpu_multigrid.h kContactPenalty says why).
    // A held one is fixed in every direction.
    dvec3 normal = dvec3(cgContacts[3u * k].xyz);
    double penalty = 1e1lf * (centre[0][0] + centre[1][1] + centre[2][2]) / 3.0lf;
    if (contactHeld(k))
        centre += dmat3(penalty);
    else if (normal != dvec3(0.0lf))
        centre += penalty * outerProduct(normal, normal);
#endif
    storeBlock(blockAt(0, k, stencilSlot(0, 0)), centre);
}
