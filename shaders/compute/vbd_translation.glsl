// vbd's translation step, the terms of one free vertex k (src/cpu/cpu_vbd_translation.cpp
// vbdTranslationTerms): its inertia and drag, its friction and contact hold (10⁴ m/h² along the
// push of its last Newton step's projection), and the grab if it holds k. Needs vbd_local.glsl,
// grab.glsl and, with colliders, vbdContacts.

const float kContactStiffness = 1e4;  // × m/h²

// Adds k's terms to l; returns its m/h².
float addVbdTranslationTerms(inout VbdLocal l, uint k, vec4 x4) {
    float h = params.dt, mass = 1.0 / x4.w;
    vec3 d = vbdDisplacement[k].xyz;
    addVbdInertia(l, d, vbdInertial[k].xyz, mass, h, params.dampingRate);
    float inertia = mass / (h * h);
#ifdef HAS_COLLIDERS
    vec4 contact = vbdContacts[2u * k], slide = vbdContacts[2u * k + 1u];
    addVbdFriction(l, d - slide.xyz, contact.xyz, contact.w, h * VBD_STICK_SPEED);
    if (slide.w > 0.0) addOuter(l, kContactStiffness * inertia, contact.xyz);
#endif
    if (grabbed(k)) {
        l.gradient -= grabForce(x4.xyz, uGrab.xyz, uGrab.w);
        addDiagonal(l, uGrab.w);
    }
    return inertia;
}
