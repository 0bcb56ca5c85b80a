// The scene's colliders in its order (DESIGN.md §2 "Order inside one step", docs/colliders.md
// §9), read from the Colliders block (layout.glsl) as src/gpu/gpu_collider_table.h lays it out:
// one record per collider, the meshes' SDF samples, and the moving colliders' poses for a batch
// of steps. The host generates COLLIDERS_IN_SCENE_ORDER from the scene, so a scene compiles the
// shapes it declares and nothing else.

// A plain plane or sphere (no thickness, friction or motion) takes the one contact response with
// h = 0, c_f = 0, v_c = 0, which is DESIGN.md §2's rule to the bit (tests/model/
// collider_contact_test.cpp; the compiler folds the zeros away).
#ifdef HAS_PLANES
#ifndef HAS_CONTACT_PLANES
#define HAS_CONTACT_PLANES
#endif
#endif
#ifdef HAS_SPHERES
#ifndef HAS_CONTACT_SPHERES
#define HAS_CONTACT_SPHERES
#endif
#endif
#if defined(HAS_PLANES) || defined(HAS_SPHERES)
#ifndef HAS_CONTACT
#define HAS_CONTACT
#endif
#endif

#ifdef HAS_CONTACT
#ifdef HAS_MESHES
// Sample `index` of the whole block, four floats per vec4: no storage block of its own (rk4
// already binds many, and llvmpipe limits them per shader).
float sdfValue(int index) { return colliders[index >> 2][index & 3]; }
#endif
#include "../colliders/collider_shapes.glsl"
#ifdef HAS_MESHES
#include "../colliders/collider_grid.glsl"
#endif
#include "../colliders/collider_contact.glsl"

#ifdef HAS_PLANES
// A plain plane record: (point, 0), (unit normal, 0); no thickness, friction or motion.
void respondPlane(vec3 point, vec3 normal, inout vec3 p, inout vec3 v) {
    respondContact(planeContact(p, point, normal), 0.0, 0.0, vec3(0.0), p, v);
}
#endif

// Record r of a collider with a thickness, friction or motion: colliders[r] = (h, c_f, 0, 0),
// the shape from r + 1 (gpu::ContactRecord, then the shape's record of src/gpu/gpu_layout.h).
// vc: the collider's velocity at the vertex (0 for a still one).
#ifdef HAS_CONTACT_PLANES
// (point, 0), (unit normal, 0).
void collidePlaneRecord(int r, vec3 vc, inout vec3 p, inout vec3 v) {
    vec4 c = planeContact(p, colliders[r + 1].xyz, colliders[r + 2].xyz);
    respondContact(c, colliders[r].x, colliders[r].y, vc, p, v);
}
#endif

#ifdef HAS_CONTACT_SPHERES
// (centre, radius).
void collideSphereRecord(int r, vec3 vc, inout vec3 p, inout vec3 v) {
    vec4 s = colliders[r + 1];
    respondSphere(s.xyz, s.w, colliders[r].x, colliders[r].y, vc, p, v);
}
#endif

#if defined(HAS_BOXES) || defined(HAS_MESHES)
mat3 recordRotation(int r) {
    return mat3(colliders[r].xyz, colliders[r + 1].xyz, colliders[r + 2].xyz);
}
#endif

#ifdef HAS_BOXES
// (centre, 0), (half extents, 0), the rotation's columns (box axes in the world).
void collideBoxRecord(int r, vec3 vc, inout vec3 p, inout vec3 v) {
    vec4 c = boxContact(p, colliders[r + 1].xyz, colliders[r + 2].xyz, recordRotation(r + 3));
    respondContact(c, colliders[r].x, colliders[r].y, vc, p, v);
}
#endif

#ifdef HAS_CAPSULES
// (a, radius), (b, 0).
void collideCapsuleRecord(int r, vec3 vc, inout vec3 p, inout vec3 v) {
    vec4 a = colliders[r + 1];
    vec4 c = capsuleContact(p, a.xyz, colliders[r + 2].xyz, a.w);
    respondContact(c, colliders[r].x, colliders[r].y, vc, p, v);
}
#endif

#ifdef HAS_MESHES
// (grid origin, cell), (sample counts, first sample) as int bits, the pose's rotation columns,
// (translation, 0).
void collideMeshRecord(int r, vec3 vc, inout vec3 p, inout vec3 v) {
    vec4 grid = colliders[r + 1];
    ivec4 count = floatBitsToInt(colliders[r + 2]);
    vec4 c = gridContact(p, grid.xyz, grid.w, count.xyz, count.w, recordRotation(r + 3),
                         colliders[r + 6].xyz);
    respondContact(c, colliders[r].x, colliders[r].y, vc, p, v);
}
#endif

#ifdef HAS_MOVING_COLLIDERS
// docs/colliders.md §3: v_c(p) = linear + angular × (p − origin), from the record's (linear, 0),
// (angular, 0), (origin, 0) at w.
vec3 colliderVelocity(int w, vec3 p) {
    return colliders[w].xyz + cross(colliders[w + 1].xyz, p - colliders[w + 2].xyz);
}
#endif
#endif  // HAS_CONTACT

#ifdef HAS_MOVING_COLLIDERS
// The first vec4 of step `step`'s slot in the pose batch (the host posed it at that step's end).
int poseSlot(uint step) {
    return POSE_BASE + int((step - 1u) % uint(POSE_BATCH)) * POSE_STRIDE;
}
#endif

#ifdef HAS_FOLLOW_PINS
// A pin that follows a collider (docs/colliders.md §5) at the end of step `step`: its rest
// position x0 through the collider's motion, x = R x0 + T, with the velocity v_c(x) there, from
// the FollowRecord (rotation columns, translation, linear, angular, origin) at `f` in the slot.
void followPin(uint step, int f, vec3 x0, out vec3 p, out vec3 vel) {
    int r = poseSlot(step) + f;
    p = mat3(colliders[r].xyz, colliders[r + 1].xyz, colliders[r + 2].xyz) * x0 +
        colliders[r + 3].xyz;
    vel = colliders[r + 4].xyz + cross(colliders[r + 5].xyz, p - colliders[r + 6].xyz);
}
#endif

// Every collider on one vertex at the end of step `step`. A moving collider's record lies in
// the slot of its step in the pose batch (the host posed it at t = step·Δt); its velocity is
// evaluated at the vertex before the projection moves it, as on the CPU.
void applyColliders(uint step, inout vec3 p, inout vec3 vel) {
#ifdef HAS_MOVING_COLLIDERS
    int pose = poseSlot(step);
#endif
#ifdef HAS_PLANES
#define PLANE(r) respondPlane(colliders[r].xyz, colliders[(r) + 1].xyz, p, vel);
#endif
#ifdef HAS_SPHERES
#define SPHERE(r) respondSphere(colliders[r].xyz, colliders[r].w, 0.0, 0.0, vec3(0.0), p, vel);
#endif
#ifdef HAS_CONTACT
#define STILL(fn, r) fn(r, vec3(0.0), p, vel);
#endif
#ifdef HAS_MOVING_COLLIDERS
#define MOVING(fn, r, w) fn(r, colliderVelocity(w, p), p, vel);
#endif
    COLLIDERS_IN_SCENE_ORDER
}

#ifdef HAS_CONTACT
// The colliders on p as applyColliders moves it (CpuColliders::project), and the surface that
// touches it last in scene order: its velocity v_c (0 for a still one) and friction coefficient
// c_f, both 0 where none touches.
void colliderSurface(uint step, inout vec3 p, out vec3 vc, out float friction) {
#ifdef HAS_MOVING_COLLIDERS
    int pose = poseSlot(step);
#endif
    vec3 vel = vec3(0.0), before;
    vc = vec3(0.0);
    friction = 0.0;
#undef PLANE
#undef SPHERE
#undef STILL
#undef MOVING
#ifdef HAS_PLANES
#define PLANE(r) before = p; respondPlane(colliders[r].xyz, colliders[(r) + 1].xyz, p, vel); \
    if (p != before) { vc = vec3(0.0); friction = 0.0; }
#endif
#ifdef HAS_SPHERES
#define SPHERE(r) before = p; \
    respondSphere(colliders[r].xyz, colliders[r].w, 0.0, 0.0, vec3(0.0), p, vel); \
    if (p != before) { vc = vec3(0.0); friction = 0.0; }
#endif
#ifdef HAS_CONTACT
#define STILL(fn, r) before = p; fn(r, vec3(0.0), p, vel); \
    if (p != before) { vc = vec3(0.0); friction = colliders[r].y; }
#endif
#ifdef HAS_MOVING_COLLIDERS
#define MOVING(fn, r, w) before = p; { vec3 u = colliderVelocity(w, p); fn(r, u, p, vel); \
    if (p != before) { vc = u; friction = colliders[r].y; } }
#endif
    COLLIDERS_IN_SCENE_ORDER
}

vec3 colliderSurfaceVelocity(uint step, vec3 p) {
    vec3 vc;
    float friction;
    colliderSurface(step, p, vc, friction);  // (p is this function's copy)
    return vc;
}
#endif
