// lagmb._core: translation only. numpy in and out, C++ errors to Python
// errors. One file per part (common.hpp lists them); this one makes the
// module and translates the errors.
#include "common.hpp"

namespace lagmb::python {

void bind_errors(py::module_& m) {
  m.doc() = "lagmb C++ core (planar multibody dynamics, SUNDIALS IDA)";
  m.attr("sundials_version") = sundials_version();
  m.def("compare_vector_operations", &compare_vector_operations, py::arg("n"), py::arg("seed") = 1,
        "lagmb's SUNDIALS vector operations against SUNDIALS' own (largest relative difference per operation).");

  py::register_exception<ModelError>(m, "ModelError", PyExc_ValueError);
  g_simulation_error = PyErr_NewException("lagmb._core.SimulationError", PyExc_RuntimeError, nullptr);
  g_assembly_error = PyErr_NewException("lagmb._core.AssemblyError", g_simulation_error.ptr(), nullptr);
  // a user function failed outside a dynamic run (equilibrium, a one-instant solve)
  g_user_function_error = PyErr_NewException("lagmb._core.UserFunctionError", g_simulation_error.ptr(), nullptr);
  m.attr("SimulationError") = g_simulation_error;
  m.attr("AssemblyError") = g_assembly_error;
  m.attr("UserFunctionError") = g_user_function_error;
  py::register_exception_translator([](std::exception_ptr p) {
    // the exception a user function raised, if it led here
    auto raise = [](py::handle type, py::object err) {
      if (t_pending_cause) {
        PyException_SetCause(err.ptr(), static_cast<py::object*>(t_pending_cause.get())->inc_ref().ptr());
        t_pending_cause.reset();
      }
      PyErr_SetObject(type.ptr(), err.ptr());
    };
    try {
      if (p) std::rethrow_exception(p);
    } catch (Interrupted& e) {
      // the user's KeyboardInterrupt (or SystemExit) itself, with the outputs so far
      py::object err = e.cause ? *static_cast<py::object*>(e.cause.get())
                               : py::reinterpret_borrow<py::object>(PyExc_KeyboardInterrupt)();
      if (e.partial.size() > 0) {
        err.attr("partial") = to_python(std::move(e.partial));
        err.attr("t") = e.t;
      }
      PyErr_SetObject(reinterpret_cast<PyObject*>(Py_TYPE(err.ptr())), err.ptr());
    } catch (const AssemblyError& e) {
      py::object err = py::reinterpret_borrow<py::object>(g_assembly_error)(e.what());
      err.attr("t") = e.t;
      err.attr("violated") = e.violated;
      err.attr("partial") = py::none();
      raise(g_assembly_error, err);
    } catch (const SimulationError& e) {
      py::object err = py::reinterpret_borrow<py::object>(g_simulation_error)(e.what());
      err.attr("t") = e.t;
      err.attr("partial") = to_python(Trajectory(e.partial));
      raise(g_simulation_error, err);
    } catch (const UserFunctionError& e) {
      py::object err = py::reinterpret_borrow<py::object>(g_user_function_error)(e.what());
      err.attr("t") = NAN;
      err.attr("partial") = py::none();
      raise(g_user_function_error, err);
    }
  });

  py::register_exception<EquilibriumError>(m, "EquilibriumError", m.attr("ModelError"));
}

}  // namespace lagmb::python

PYBIND11_MODULE(_core, m) {
  using namespace lagmb::python;
  bind_errors(m);
  bind_functions(m);
  bind_model(m);
  bind_runs(m);
  bind_fmu(m);
  bind_statics(m);
}
