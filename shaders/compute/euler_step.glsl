// Pass 2 of explicit_euler and symplectic_euler for one vertex (DESIGN.md §2 "Order inside one
// step"): integrate with the force of pass 1, then pins, colliders and the instability check
// (step_end.glsl). Shared by integrate.comp and many_steps.comp.
void integrateVertex(uint step, uint k) {
    vec4 x = positions[k], v = velocities[k];
    vec3 p = x.xyz, vel = v.xyz;
    integrate(p, vel, forces[k].xyz, x.w, params.dt, params.dampingRate, params.gravity);
    finishStep(step, k, x, v, p, vel);
}
