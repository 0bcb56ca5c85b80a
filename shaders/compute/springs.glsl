// The scene's spring families as one table (src/model/grid.h's kSpringOffsets, the seed's Q10):
// the force pass and the stiffness product walk the same rows.

#if NUM_SPRING_OFFSETS > 0
// The active rows of kSpringOffsets, generated from that table by the host:
// (di, dj, family, slot); the slot indexes the stiffness and rest length of Params. A family the
// scene does not model has no row.
const ivec4 kSpringOffsets[NUM_SPRING_OFFSETS] = ivec4[](SPRING_OFFSETS);
#endif

float springStiffness(ivec4 s) { return params.stiffness[s.w / 4][s.w % 4]; }    // K [N/m]

// K of spring s at vertex ij [N/m]: with HAS_BORDER_SHARES (a material), a structural spring on
// a border line, both ends on the first or last row (along u) or column (along v), stands for
// half a cell of cloth and has half the stiffness (src/model/grid.h onBorderLine).
float springStiffnessAt(ivec4 s, ivec2 ij) {
#ifdef HAS_BORDER_SHARES
    bool onBorder = (s.y == 0 && (ij.y == 0 || ij.y == gridV() - 1)) ||
                    (s.x == 0 && (ij.x == 0 || ij.x == gridU() - 1));
    if (s.z == 0 && onBorder) return 0.5 * springStiffness(s);
#endif
    return springStiffness(s);
}
float springRestLength(ivec4 s) { return params.restLength[s.w / 4][s.w % 4]; }  // L [m]

#ifdef HAS_SPRING_DAMPING
// βK [N·s/m] of spring s at vertex ij: its damping along the spring (docs/physics.md "Spring
// damping"), with the K of springStiffnessAt (half on a material's border line).
float springDampingAt(ivec4 s, ivec2 ij) { return params.springDamping * springStiffnessAt(s, ij); }

// Damping along a spring, src/model/spring_math.h addSpringDamping: βK ((w·d)/|d|²) d with
// d = x_q − x_k and w = w_q − w_k (velocities: the force; any field: −(∂F/∂v) w). Nothing for a
// spring squeezed below 1e-12 L.
vec3 springDampingForce(vec3 d, vec3 w, float dampingK, float restLength) {
    float d2 = dot(d, d), floorLength = 1e-12 * restLength;
    return d2 >= floorLength * floorLength ? (dampingK * dot(w, d) / d2) * d : vec3(0.0);
}
#endif
