// Evaluates the GLSL collider functions of shaders/colliders/ at a buffer of points, for
// tests/gpu/gpu_colliders_test.cpp to compare with src/model/collider_shapes.h and
// collider_contact.h. Per point k (input: p, v, v_c as vec4s 3k..3k+2) it writes eight vec4s:
// plane, sphere, box, capsule and grid contacts (n, φ); then p and v after the box's response
// (w = 1 if it touched) and p after the sphere's.
layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Inputs { vec4 inputs[]; };
layout(std430, binding = 1) writeonly buffer Outputs { vec4 outputs[]; };
layout(std430, binding = 2) readonly buffer GridValues { float gridValues[]; };

float sdfValue(int index) { return gridValues[index]; }

// Every shape (the solver's kernels define only the scene's).
#define HAS_CONTACT_PLANES
#define HAS_CONTACT_SPHERES
#define HAS_BOXES
#define HAS_CAPSULES
#include "../../../shaders/colliders/collider_shapes.glsl"
#include "../../../shaders/colliders/collider_grid.glsl"
#include "../../../shaders/colliders/collider_contact.glsl"

layout(location = 0) uniform int pointCount;
layout(location = 1) uniform vec3 planePoint;
layout(location = 2) uniform vec3 planeNormal;
layout(location = 3) uniform vec4 sphere;  // centre, radius
layout(location = 4) uniform vec3 boxCenter;
layout(location = 5) uniform vec3 boxHalf;
layout(location = 6) uniform mat3 boxRotation;
layout(location = 7) uniform vec4 capsuleA;  // a, radius
layout(location = 8) uniform vec3 capsuleB;
layout(location = 9) uniform vec4 gridOrigin;  // origin, cell
layout(location = 10) uniform ivec3 gridCount;
layout(location = 11) uniform mat3 gridRotation;
layout(location = 12) uniform vec3 gridTranslation;
layout(location = 13) uniform vec2 contactParams;  // thickness, friction

void main() {
    int k = int(gl_GlobalInvocationID.x);
    if (k >= pointCount) return;
    vec3 p = inputs[3 * k].xyz, v = inputs[3 * k + 1].xyz, vc = inputs[3 * k + 2].xyz;
    outputs[8 * k + 0] = planeContact(p, planePoint, planeNormal);
    outputs[8 * k + 1] = sphereContact(p, sphere.xyz, sphere.w);
    outputs[8 * k + 2] = boxContact(p, boxCenter, boxHalf, boxRotation);
    outputs[8 * k + 3] = capsuleContact(p, capsuleA.xyz, capsuleB, capsuleA.w);
    outputs[8 * k + 4] = gridContact(p, gridOrigin.xyz, gridOrigin.w, gridCount, 0, gridRotation,
                                     gridTranslation);
    vec3 pb = p, vb = v;
    bool touched = respondContact(boxContact(p, boxCenter, boxHalf, boxRotation),
                                  contactParams.x, contactParams.y, vc, pb, vb);
    outputs[8 * k + 5] = vec4(pb, touched ? 1.0 : 0.0);
    outputs[8 * k + 6] = vec4(vb, 0.0);
    vec3 ps = p, vs = v;
    respondSphere(sphere.xyz, sphere.w, contactParams.x, contactParams.y, vc, ps, vs);
    outputs[8 * k + 7] = vec4(ps, 0.0);
}
