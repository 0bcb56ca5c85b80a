// implicit_euler's contacts inside the solve (docs/integrators.md, "Contact in the solve";
// src/model/solve_contact.h is the CPU's copy): per vertex (n, z), n the unit normal of a
// contact predicted for the end of the step (0: none) and z = ⟨n, Δv⟩ the velocity change it
// fixes. S w = w − n ⟨n, w⟩ filters the conjugate gradient's r, A p and z.
#ifdef HAS_SOLVE_CONTACTS
layout(std430, binding = 17) buffer CgContacts {
    vec4 cgContacts[];
};

vec3 filterContact(uint k, vec3 w) {
    vec3 n = cgContacts[k].xyz;
    return w - n * dot(n, w);
}
#else
vec3 filterContact(uint k, vec3 w) { return w; }
#endif
