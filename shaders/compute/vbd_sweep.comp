// vbd, one colour of a sweep (docs/integrators.md "vbd"; src/cpu/cpu_vbd.cpp vbdVertex): every
// free vertex with (i + 2j) mod 5 = uVbd takes one Newton step on its local G (with its
// contact's friction), then the colliders' projection, which sets the contact (vbdTouch). Vertices
// of one colour share no energy term: one dispatch per colour, no atomics. The dispatch covers
// the colour's vertices only: invocation (m, j) is row j's m-th, i = first(j) + 5m.
#include "layout.glsl"
#include "common.glsl"
#include "springs.glsl"
#include "grab.glsl"
#include "step_end.glsl"
#ifdef HAS_BENDING
#define BENDING_FIELD(q) positions[vertexIndex(q)].xyz
#include "bending.glsl"
#endif
#include "vbd_local.glsl"

layout(local_size_x = WX, local_size_y = WY) in;

layout(location = 3) uniform int uVbd;  // the colour

void main() {
    ivec2 cell = ivec2(gl_GlobalInvocationID.xy);
    int first = (uVbd + 10 - (2 * cell.y) % 5) % 5;  // (first + 2j) mod 5 = uVbd, all >= 0
    ivec2 ij = ivec2(first + 5 * cell.x, cell.y);
    if (ij.x >= gridU() || ij.y >= gridV() || frozen(uStep)) return;
    uint k = vertexIndex(ij);
    vec4 x4 = positions[k];
    if (x4.w == 0.0) return;  // pinned
    float h = params.dt, mass = 1.0 / x4.w;
    vec3 x = x4.xyz, d = vbdDisplacement[k].xyz;  // the iterate: position, displacement x − x_n
    VbdLocal l = vbdLocalZero();
    addVbdInertia(l, d, vbdInertial[k].xyz, mass, h, params.dampingRate);
#if NUM_SPRING_OFFSETS > 0
    for (int o = 0; o < NUM_SPRING_OFFSETS; ++o) {
        ivec4 s = kSpringOffsets[o];
        ivec2 q = ij + s.xy;
        if (!insideGrid(q)) continue;
        uint kq = vertexIndex(q);
        vec3 xq = positions[kq].xyz;
        addVbdSpring(l, x, xq, springStiffnessAt(s, ij), springRestLength(s));
#ifdef HAS_SPRING_DAMPING
        addVbdSpringDamping(l, xq - x, vbdDisplacement[kq].xyz - d, springDampingAt(s, ij),
                            springRestLength(s), h);
#endif
    }
#endif
#ifdef HAS_BENDING
    l.gradient -= bendingForce(ij, params.bending.xyz);
    addDiagonal(l, vbdBendingDiagonal(ij, params.bending.xyz));
#endif
    if (grabbed(k)) {
        l.gradient -= grabForce(x, uGrab.xyz, uGrab.w);
        addDiagonal(l, uGrab.w);
    }
#ifdef HAS_COLLIDERS
    vec4 contact = vbdContacts[2u * k];
    addVbdFriction(l, d - vbdContacts[2u * k + 1u].xyz, contact.xyz, contact.w,
                   h * VBD_STICK_SPEED);
#endif
    vec3 step;
    if (!vbdNewtonStep(l, mass / (h * h), step)) return;
    x += step;
    d += step;
#ifdef HAS_COLLIDERS
    vec3 p = x, vc;
    float friction;
    colliderSurface(uStep, p, vc, friction);  // the projection, and the surface it met
    vec3 push = p - x;
    float pushed = length(push);
    if (pushed > 0.0) {  // the contact for the next sweep (vbdTouch): n, c_f λ, h v_c
        vbdContacts[2u * k] = vec4(push / pushed,
                                   friction * (pushed * vbdNormalStiffness(l, push / pushed)));
        vbdContacts[2u * k + 1u] = vec4(h * vc, 1.0);
    } else {
        vbdContacts[2u * k].w = 0.0;
        vbdContacts[2u * k + 1u].w = 0.0;
    }
    d += push;
    x = p;
#endif
    positions[k] = vec4(x, x4.w);
    vbdDisplacement[k] = vec4(d, 0.0);
}
