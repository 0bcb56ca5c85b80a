#include "python/py_errors.h"

#include <initializer_list>
#include <utility>

#include "model/errors.h"
#include "python/simulation.h"

namespace py = pybind11;

namespace cloth::python {
namespace {

// The types, created once at import and held by the module (and by these, for the life of the
// process: an exception may be raised while the module is being torn down).
PyObject* sceneError = nullptr;
PyObject* unstableError = nullptr;
PyObject* gpuUnavailableError = nullptr;

constexpr const char* kSceneErrorDoc = R"doc(The scene is invalid: a missing file, bad JSON, an
unknown key, a value out of range, an override in ``set=`` that does not apply, or a scene the
chosen backend cannot run (a grid too large for the GPU's buffers). The same checks as
``clothsim run``/``validate``, with the same message (``str(error)``).

Attributes:
    file: the scene file, or ``"<dict>"`` for a scene given as a dict.
    key: the key path of the offending value, e.g. ``"cloth.resolution[0]"``; ``""`` when the
        document as a whole is wrong (no such file, not JSON).
    reason: what is wrong with it.)doc";

constexpr const char* kUnstableErrorDoc = R"doc(The simulation became unstable (docs/design.md
§2): a position or velocity not finite, a speed past ``max_speed`` or a spring strained past
``max_strain``. ``clothsim run`` exits with 3 in the same case; ``str(error)`` is its message.

The solver stopped at the unstable step: ``Simulation.steps`` counts it, and the state it holds
may not be finite. Write a state with ``set_positions``/``set_velocities`` to go on.

Attributes:
    step: the first unstable step (1-based, counted from the start of the simulation).
    last_step: the step it is known by: ``step`` where the backend checks every step; the GPU
        checks every few steps, and the first bad step lies in ``step..last_step``.
    time: the simulated time at ``step`` [s].
    reason: what went wrong, e.g. ``"speed 1.2e+04 m/s > max_speed 1e+04 at vertex (3, 7)"``.
    advice: what to change, as ``clothsim run`` says it.
    suggested_dt: the time step the advice suggests [s] (half the predicted bound; for vbd's
        strain, the step at which its sweeps held a dropped sheet of that size; for
        implicit_euler under the step control, half its step), or ``None`` where a smaller step
        is not the cure: springs too soft for the load, a method stable at any step, or explicit
        Euler without the damping to be stable at all.
    stable_dt: the integrator's predicted stability bound for the scene [s] (``inf``: any
        step; ``0``: none).)doc";

constexpr const char* kGpuUnavailableDoc = R"doc(``backend="gpu"`` was asked for and no OpenGL
4.3 context could be made (``clothsim run`` exits with 4).)doc";

PyObject* newError(py::module_& m, const char* name, PyObject* base, const char* doc,
                   std::initializer_list<std::pair<const char*, py::object>> defaults) {
    py::dict attributes;
    for (const auto& [key, value] : defaults) attributes[key] = value;
    const std::string qualified = std::string("clothsim.") + name;
    PyObject* type = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, base, attributes.ptr());
    if (type == nullptr) throw py::error_already_set();
    m.add_object(name, py::handle(type));
    return type;
}

// Sets `type(message)` as the pending exception, with the attributes set on it.
void raise(PyObject* type, const std::string& message,
           std::initializer_list<std::pair<const char*, py::object>> attributes) {
    py::object error = py::reinterpret_borrow<py::object>(type)(text(message));
    for (const auto& [key, value] : attributes) error.attr(key) = value;
    PyErr_SetObject(type, error.ptr());
}

// A path as os.fsdecode gives it (os.fsencode(error.file) is its bytes).
py::str pathText(const std::string& path) {
    PyObject* s = PyUnicode_DecodeFSDefaultAndSize(path.data(), Py_ssize_t(path.size()));
    if (s == nullptr) throw py::error_already_set();
    return py::reinterpret_steal<py::str>(s);
}

py::object optionalFloat(const std::optional<double>& x) {
    return x ? py::object(py::float_(*x)) : py::object(py::none());
}

}  // namespace

py::str text(const std::string& message) {
    PyObject* s =
        PyUnicode_DecodeUTF8(message.data(), Py_ssize_t(message.size()), "backslashreplace");
    if (s == nullptr) throw py::error_already_set();
    return py::reinterpret_steal<py::str>(s);
}

void registerErrors(py::module_& m) {
    sceneError = newError(m, "SceneError", PyExc_ValueError, kSceneErrorDoc,
                          {{"file", py::str("")}, {"key", py::str("")}, {"reason", py::str("")}});
    unstableError = newError(m, "UnstableError", PyExc_RuntimeError, kUnstableErrorDoc,
                             {{"step", py::int_(0)},
                              {"last_step", py::int_(0)},
                              {"time", py::float_(0.0)},
                              {"reason", py::str("")},
                              {"advice", py::str("")},
                              {"suggested_dt", py::none()},
                              {"stable_dt", py::float_(0.0)}});
    gpuUnavailableError =
        newError(m, "GpuUnavailableError", PyExc_RuntimeError, kGpuUnavailableDoc, {});
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const InputError& e) {
            raise(sceneError, e.what(),
                  {{"file", pathText(e.file())},
                   {"key", py::str(e.key())},
                   {"reason", py::str(e.reason())}});
        } catch (const Unstable& e) {
            raise(unstableError, e.what(),
                  {{"step", py::int_(e.result.firstBadStep)},
                   {"last_step", py::int_(e.result.lastBadStep)},
                   {"time", py::float_(e.time)},
                   {"reason", py::str(e.result.reason)},
                   {"advice", py::str(e.advice.text)},
                   {"suggested_dt", optionalFloat(e.advice.dt)},
                   {"stable_dt", py::float_(e.stableDt)}});
        } catch (const GpuUnavailable& e) {
            PyErr_SetObject(gpuUnavailableError, text(e.what()).ptr());
        }
    });
}

}  // namespace cloth::python
