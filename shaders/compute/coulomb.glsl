// Coulomb's law of the colliders at the prediction p* (src/model/solve_contact.h coulomb): the
// tangential velocity applyColliders leaves of `slide` (⟨n, slide⟩ = 0) approaching the surface
// at `approach` ≥ 0 [m/s], after a first run that finds the collider's normal velocity. The
// static branch returns the collider's v_c exactly. The including kernel declares uStep and
// includes scene_colliders.glsl.
vec3 coulomb(vec3 pStar, vec3 n, vec3 slide, float approach) {
    vec3 q = pStar, w = slide;
    applyColliders(uStep, q, w);
    q = pStar;
    w = slide + (dot(n, w) - approach) * n;
    applyColliders(uStep, q, w);
    return w - n * dot(n, w);
}

