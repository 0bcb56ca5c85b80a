// The viewer's grab (Solver::setGrab): a spring F = K (target − x) on one vertex, part of F
// like any other force, and K I in the stiffness H at that vertex. The host sets these uniforms
// in every kernel that includes this file. uGrabVertex = -1 when nothing is grabbed: one compare
// per vertex.
layout(location = 0) uniform int uGrabVertex;
layout(location = 1) uniform vec4 uGrab;  // xyz target [m], w stiffness K [N/m]

bool grabbed(uint k) { return int(k) == uGrabVertex; }
