// The Python module clothsim (README, "Python"): a Simulation over a scene, its state in and out
// as numpy arrays. The work is done in simulation.h; here are the Python types, the conversions
// and the docstrings (docstrings.h).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "model/errors.h"
#include "model/stability.h"
#include "python/docstrings.h"
#include "python/py_errors.h"
#include "python/simulation.h"
#include "scene/scene_overrides.h"

namespace py = pybind11;
using namespace py::literals;

namespace cloth::python {
namespace {

static_assert(sizeof(glm::dvec3) == 3 * sizeof(double), "an (N, 3) array's rows are dvec3s");

// An (N, 3) float64 array that owns `rows`: the solver's read() has already copied its state out
// of the backend's own layout (the CPU's arrays of x, y and z, the GPU's vec4 buffers), so the
// array takes that copy over rather than make a second one.
py::array_t<double> rowsArray(std::vector<glm::dvec3> rows) {
    auto* owned = new std::vector<glm::dvec3>(std::move(rows));
    py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<glm::dvec3>*>(p); });
    const auto n = py::ssize_t(owned->size());
    return py::array_t<double>({n, py::ssize_t(3)},
                               {py::ssize_t(sizeof(glm::dvec3)), py::ssize_t(sizeof(double))},
                               &owned->front().x, owner);
}

// The rows of an array-like of shape (N, 3) of real numbers (any float or integer dtype, taken
// as float64), N the grid's vertex count; a ValueError naming the expected shape otherwise.
std::vector<glm::dvec3> rowsFrom(const py::handle& object, const Scene& scene, const char* what) {
    const py::ssize_t n = py::ssize_t(scene.cloth.nu) * scene.cloth.nv;
    const std::string expected = std::string(what) + ": expected an array of shape (" +
                                 std::to_string(n) + ", 3) (x, y, z of the " +
                                 std::to_string(scene.cloth.nu) + " x " +
                                 std::to_string(scene.cloth.nv) + " vertices, k = j*nu + i)";
    const py::array a = py::array::ensure(object);
    if (!a) throw py::value_error(expected + ", got " + std::string(py::repr(object.get_type())));
    const char kind = a.dtype().kind();
    if (kind != 'f' && kind != 'i' && kind != 'u')
        throw py::value_error(expected + " of real numbers, got dtype " +
                              std::string(py::str(a.dtype())));
    if (a.ndim() != 2 || a.shape(0) != n || a.shape(1) != 3)
        throw py::value_error(expected + ", got shape " + std::string(py::repr(a.attr("shape"))));
    const auto d = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
    std::vector<glm::dvec3> rows(static_cast<std::size_t>(n));
    std::copy_n(d.data(), 3 * n, &rows.front().x);
    return rows;
}

// What json.dumps cannot write by itself: numpy's scalars and arrays, through tolist() (an
// np.int64 is no int; an array of resolutions is a list).
py::object jsonDefault(const py::handle& value) {
    if (py::hasattr(value, "tolist")) return value.attr("tolist")();
    throw py::type_error("an object of type " +
                         std::string(py::str(value.get_type().attr("__name__"))) +
                         " is not a JSON value");
}

// `value` as JSON text (Python's json module: floats round-trip), for an override or a scene
// given as a dict; what cannot be JSON (NaN among it) is the scene's error at `key`.
std::string jsonText(const py::handle& value, const std::string& source, const std::string& key) {
    try {
        return py::module_::import("json")
            .attr("dumps")(value, "allow_nan"_a = false,
                           "default"_a = py::cpp_function(jsonDefault))
            .cast<std::string>();
    } catch (py::error_already_set& e) {
        if (!e.matches(PyExc_TypeError) && !e.matches(PyExc_ValueError)) throw;
        throw InputError(
            source, key,
            std::string("cannot be written as JSON: ") + std::string(py::str(e.value())));
    }
}

void warn(PyObject* category, const std::string& message) {
    if (PyErr_WarnEx(category, std::string(text(message)).c_str(), 1) != 0)
        throw py::error_already_set();
}

// The overrides of `integrator=` and `set=`, in that order, as `run --set` takes them; a key set
// twice keeps the later value and says so, as `run` does.
std::vector<std::string> overrides(const std::optional<std::string>& integrator,
                                   const py::object& set, const std::string& source) {
    std::vector<std::pair<std::string, py::object>> items;
    if (integrator) items.emplace_back("integrator.method", py::str(*integrator));
    if (!set.is_none()) {
        if (!py::isinstance(set, py::module_::import("collections.abc").attr("Mapping")))
            throw py::type_error("set: expected a dict of KEY.PATH: value, got " +
                                 std::string(py::repr(set.get_type())));
        for (const auto& item : set.attr("items")()) {
            const py::tuple kv = py::reinterpret_borrow<py::tuple>(item);
            if (!py::isinstance<py::str>(kv[0]))
                throw py::type_error("set: keys are key paths such as \"material.stretch\", got " +
                                     std::string(py::repr(kv[0])));
            if (py::len(kv[0]) == 0)
                throw InputError(source, "set",
                                 "an empty key: keys are key paths such as \"material.stretch\"");
            items.emplace_back(kv[0].cast<std::string>(),
                               py::reinterpret_borrow<py::object>(kv[1]));
        }
    }
    std::vector<std::string> sets;
    for (const auto& [key, value] : items) {
        std::string assignment = key + "=" + jsonText(value, source, key);
        for (const std::string& notice : replacedOverrides(sets, assignment))
            warn(PyExc_UserWarning, notice);
        sets.push_back(std::move(assignment));
    }
    return sets;
}

std::unique_ptr<Simulation> makeSimulation(const py::object& scene,
                                           const std::optional<std::string>& backend,
                                           const std::optional<std::string>& precision,
                                           const std::optional<std::string>& integrator,
                                           const std::optional<int>& threads,
                                           const py::object& set) {
    const py::module_ os = py::module_::import("os");
    const bool isPath = py::isinstance<py::str>(scene) || py::isinstance<py::bytes>(scene) ||
                        py::isinstance(scene, os.attr("PathLike"));
    const bool isDict =
        py::isinstance(scene, py::module_::import("collections.abc").attr("Mapping"));
    if (!isPath && !isDict)
        throw py::type_error("scene: expected a path or a dict, got " +
                             std::string(py::repr(scene.get_type())));
    // A path's bytes as the file system takes them (os.fsencode): any str, bytes or PathLike,
    // UTF-8 or not; an embedded NUL is refused, as Python's open refuses it.
    const std::string source =
        isPath ? os.attr("fsencode")(scene).cast<py::bytes>().cast<std::string>() : "<dict>";
    if (source.find('\0') != std::string::npos)
        throw py::value_error("scene: embedded null byte in the path " +
                              std::string(py::repr(scene)));
    Options options{backend.value_or(""), precision.value_or(""), threads,
                    overrides(integrator, set, source)};
    std::unique_ptr<Simulation> sim =
        isPath ? Simulation::load(source, options)
               : Simulation::parse(jsonText(scene, source, ""), source, options);
    if (const auto warning = dtWarning(sim->scene()))
        warn(PyExc_RuntimeWarning, source + ": " + *warning);
    return sim;
}

// Between runs of steps: Ctrl+C (or any signal handler that raises) stops a long step(n).
void checkSignals() {
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
}

std::string describe(const Simulation& s) {
    const Scene& scene = s.scene();
    char buf[96];
    std::snprintf(buf, sizeof buf, " %dx%d, %s, step %ld, t = %.6g s", scene.cloth.nu,
                  scene.cloth.nv, methodName(scene.integrator.method), s.solver().stepsDone(),
                  s.solver().time());
    return "<clothsim.Simulation '" + scene.name + "'" + buf + " (" + s.solver().name() + ")>";
}

void bindResults(py::module_& m) {
    py::class_<Energy>(m, "Energy", doc::kEnergy)
        .def_readonly("kinetic", &Energy::kinetic, "Sum of 1/2 m |v|^2 over the vertices [J].")
        .def_readonly("spring", &Energy::spring, "Sum of 1/2 K (|d| - L)^2 over the springs [J].")
        .def_readonly("gravity", &Energy::gravity, "-Sum of m <g, p> over the vertices [J].")
        .def_readonly("bending", &Energy::bending, "A material's bending energy [J] (0 without).")
        .def_property_readonly(
            "potential", [](const Energy& e) { return e.spring + e.gravity + e.bending; },
            "spring + gravity + bending [J].")
        .def_property_readonly("total", &Energy::total, "kinetic + potential [J].")
        .def("__repr__", [](const Energy& e) {
            char buf[160];
            std::snprintf(buf, sizeof buf,
                          "Energy(kinetic=%.6g, spring=%.6g, gravity=%.6g, bending=%.6g)",
                          e.kinetic, e.spring, e.gravity, e.bending);
            return std::string(buf);
        });
    py::class_<SolveStats>(m, "SolveStats", doc::kSolveStats)
        .def_readonly("solves", &SolveStats::solves, "Linear solves done.")
        .def_readonly("iterations", &SolveStats::iterations, "CG iterations, summed over solves.")
        .def_readonly("most_iterations", &SolveStats::mostIterations, "Most in one solve.")
        .def_readonly("misses", &SolveStats::misses,
                      "Solves that did not reach the tolerance: stopped at "
                      "integrator.max_iterations, or broke down.")
        .def_readonly("breakdowns", &SolveStats::breakdowns,
                      "Misses that broke down before the cap (p·A p <= 0 or a sum not finite).")
        .def_readonly("first_breakdown_step", &SolveStats::firstBreakdownStep,
                      "1-based step of the first breakdown (0: none).")
        .def_readonly("first_miss_step", &SolveStats::firstMissStep,
                      "1-based step of the first miss (0: none).")
        .def_readonly("worst_residual", &SolveStats::worstResidual,
                      "Largest final |r|/|b| of a miss.")
        .def_readonly("last_iterations", &SolveStats::lastIterations, "The last solve's.")
        .def_readonly("last_residual", &SolveStats::lastResidual, "The last solve's final |r|/|b|.")
        .def_readonly("last_converged", &SolveStats::lastConverged,
                      "Whether the last solve reached the tolerance.")
        .def("__repr__", [](const SolveStats& s) {
            return "SolveStats(solves=" + std::to_string(s.solves) +
                   ", iterations=" + std::to_string(s.iterations) +
                   ", misses=" + std::to_string(s.misses) + ")";
        });
    py::class_<StepControlStats>(m, "StepControlStats", doc::kStepControlStats)
        .def_readonly("split", &StepControlStats::split,
                      "Steps of integrator.dt taken as two halves or more.")
        .def_readonly("rejected", &StepControlStats::rejected, "Tries thrown away, at every depth.")
        .def_readonly("substeps", &StepControlStats::substeps, "Steps the backend took and kept.")
        .def_readonly("deepest", &StepControlStats::deepest,
                      "Most halvings of one step: its shortest piece is dt / 2**deepest.")
        .def("__repr__", [](const StepControlStats& s) {
            return "StepControlStats(split=" + std::to_string(s.split) +
                   ", rejected=" + std::to_string(s.rejected) +
                   ", substeps=" + std::to_string(s.substeps) +
                   ", deepest=" + std::to_string(s.deepest) + ")";
        });
}

using PySimulation = py::class_<Simulation>;

// What a Simulation is: its scene, solver and clock.
void bindRun(PySimulation& c) {
    c.def(py::init(&makeSimulation), "scene"_a, py::kw_only(), "backend"_a = py::none(),
          "precision"_a = py::none(), "integrator"_a = py::none(), "threads"_a = py::none(),
          "set"_a = py::none(), doc::kInit)
        .def(
            "step", [](Simulation& s, long n) { s.step(n, checkSignals); }, "n"_a = 1, doc::kStep)
        .def_property_readonly(
            "time", [](const Simulation& s) { return s.solver().time(); },
            "Simulated time [s] after the steps done.")
        .def_property_readonly(
            "steps", [](const Simulation& s) { return s.solver().stepsDone(); },
            "Steps done since the simulation was made.")
        .def_property_readonly(
            "dt", [](const Simulation& s) { return s.scene().integrator.dt; },
            "The time step integrator.dt [s].")
        .def_property_readonly(
            "shape",
            [](const Simulation& s) {
                return py::make_tuple(s.scene().cloth.nu, s.scene().cloth.nv);
            },
            "(nu, nv): the grid's vertices along u and v; vertex (i, j) is row j*nu + i.")
        .def_property_readonly(
            "name", [](const Simulation& s) { return s.scene().name; }, "The scene's name.")
        .def_property_readonly(
            "integrator",
            [](const Simulation& s) { return methodName(s.scene().integrator.method); },
            "The integrator's method name, e.g. \"symplectic_euler\".")
        .def_property_readonly(
            "backend", [](const Simulation& s) { return s.solver().name(); },
            "The solver, as `clothsim run` names it: \"cpu double avx512, 1 thread\".")
        .def_property_readonly(
            "stable_dt", [](const Simulation& s) { return stableDt(s.scene()); }, doc::kStableDt);
}

// Its state in and out, and the pins.
void bindState(PySimulation& c) {
    c.def_property_readonly(
         "positions", [](const Simulation& s) { return rowsArray(s.state().positions); },
         doc::kPositions)
        .def_property_readonly(
            "velocities", [](const Simulation& s) { return rowsArray(s.state().velocities); },
            doc::kVelocities)
        .def(
            "set_positions",
            [](Simulation& s, const py::handle& a) {
                s.setPositions(rowsFrom(a, s.scene(), "positions"));
            },
            "positions"_a, doc::kSetPositions)
        .def(
            "set_velocities",
            [](Simulation& s, const py::handle& a) {
                s.setVelocities(rowsFrom(a, s.scene(), "velocities"));
            },
            "velocities"_a, doc::kSetVelocities)
        .def(
            "pin", [](Simulation& s, int i, int j) { s.setPinned(i, j, true); }, "i"_a, "j"_a,
            doc::kPin)
        .def(
            "unpin", [](Simulation& s, int i, int j) { s.setPinned(i, j, false); }, "i"_a, "j"_a,
            doc::kUnpin);
}

// What is measured on its state.
void bindMeasures(PySimulation& c) {
    c.def(
         "energy", [](const Simulation& s) { return energy(s.scene(), s.state()); },
         doc::kEnergyMethod)
        .def(
            "max_strain", [](const Simulation& s) { return maxStrain(s.scene(), s.state()); },
            doc::kMaxStrain)
        .def(
            "largest_strain",
            [](const Simulation& s) {
                const SpringStrain w = largestStrain(s.scene(), s.state());
                const int nu = s.scene().cloth.nu;
                return py::make_tuple(w.strain, py::make_tuple(w.a % nu, w.a / nu),
                                      py::make_tuple(w.b % nu, w.b / nu));
            },
            doc::kLargestStrain)
        .def_property_readonly(
            "solve_stats", [](const Simulation& s) { return s.solver().solveStats(); },
            doc::kSolveStatsProperty)
        .def_property_readonly(
            "step_control_stats", [](const Simulation& s) { return s.solver().stepControlStats(); },
            doc::kStepControlStatsProperty);
}

void bindSimulation(py::module_& m) {
    PySimulation c(m, "Simulation", doc::kSimulation);
    bindRun(c);
    bindState(c);
    bindMeasures(c);
    c.def("__repr__", &describe);
}

}  // namespace
}  // namespace cloth::python

PYBIND11_MODULE(clothsim, m) {
    using namespace cloth::python;
    m.doc() = doc::kModule;
    registerErrors(m);
    bindResults(m);
    bindSimulation(m);
}
