// The scene's spring families as one table (src/model/grid.h's kSpringOffsets, the seed's Q10):
// the force pass and the stiffness product walk the same rows.

#if NUM_SPRING_OFFSETS > 0
// The active rows of kSpringOffsets, generated from that table by the host:
// (di, dj, family, slot); the slot indexes the stiffness and rest length of Params. A family the
// scene does not model has no row.
const ivec4 kSpringOffsets[NUM_SPRING_OFFSETS] = ivec4[](SPRING_OFFSETS);
#endif

float springStiffness(ivec4 s) { return params.stiffness[s.w / 4][s.w % 4]; }    // K [N/m]
float springRestLength(ivec4 s) { return params.restLength[s.w / 4][s.w % 4]; }  // L [m]
