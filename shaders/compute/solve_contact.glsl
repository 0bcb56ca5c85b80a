// implicit_euler's contacts inside the solve (docs/integrators.md, "Contact in the solve";
// src/model/solve_contact.h is the CPU's copy and explains the stick and slip): three vec4 per
// vertex,
//   [3k]     (n, z): n the unit normal of a contact predicted for the end of the step (0: none),
//            z = ⟨n, Δv⟩ the velocity change it fixes;
//   [3k + 1] (hold, grip): a held contact's tangential velocity change S (v_c − v) (else 0), and
//            the grip kept from step to step (0 none, > 0 sliding with the last solve's normal
//            impulse J_n, < 0 held);
//   [3k + 2] (b, stuck): the right-hand side b_k for the impulse J = (A Δv)_k − b_k after the
//            solve, and 1 where the friction in b stopped the slide (held in the next step).
// S w = w − n ⟨n, w⟩ filters the conjugate gradient's r, A p and z; a held contact filters to 0.
#ifdef HAS_SOLVE_CONTACTS
layout(std430, binding = 17) buffer CgContacts {
    vec4 cgContacts[];
};

bool contactHeld(uint k) { return cgContacts[3u * k + 1u].w < 0.0; }

vec3 filterContact(uint k, vec3 w) {
    if (contactHeld(k)) return vec3(0.0);
    vec3 n = cgContacts[3u * k].xyz;
    return w - n * dot(n, w);
}

// The part of Δv the contact fixes: z n, and the tangential change of a held one.
vec3 fixedChange(uint k) {
    vec4 c = cgContacts[3u * k];
    return c.w * c.xyz + cgContacts[3u * k + 1u].xyz;
}
#else
vec3 filterContact(uint k, vec3 w) { return w; }
#endif
