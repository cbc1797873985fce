// lagmb._core: time functions, inputs and Python callables as time functions.
#include "common.hpp"

namespace lagmb::python {

void bind_functions(py::module_& m) {
  py::class_<TimeFunction, TimeFunctionPtr>(m, "TimeFunction",
                                           py::custom_type_setup(collectable<TimeFunction, OwnFunction>))
      .def("__call__",
           [](const TimeFunction& f, double t) {
             const TimeValue v = f.eval(t);
             return py::make_tuple(v.f, v.df, v.ddf);
           })
      .def_property_readonly("text", &TimeFunction::text,
                             "The function as text (\"linear 2 0\"); \"\" for a Python callable.")
      .def_property_readonly("callable",
                             [](const TimeFunction& f) -> py::object {
                               if (auto* p = dynamic_cast<const PythonTimeFunction*>(&f))
                                 return py::reinterpret_borrow<py::object>(p->callable());
                               return py::none();
                             })
      .def_property_readonly("component",
                             [](const TimeFunction& f) {
                               auto* p = dynamic_cast<const PythonTimeFunction*>(&f);
                               return p ? p->component() : -1;
                             })
      .def_property_readonly(
          "identity", [](const TimeFunction& f) { return reinterpret_cast<std::uintptr_t>(&f); },
          "A number that names this C++ function while it lives (one Input is one object).");
  m.def("constant", &constant, py::arg("c"));
  m.def("linear", &linear, py::arg("rate"), py::arg("start"));
  m.def("polynomial", &polynomial, py::arg("coeffs"));
  m.def("harmonic", &harmonic, py::arg("amplitude"), py::arg("omega"), py::arg("phase"), py::arg("offset"));
  m.def("smooth_step", &smooth_step, py::arg("t0"), py::arg("t1"), py::arg("y0"), py::arg("y1"));
  m.def("spline", &spline, py::arg("times"), py::arg("values"));
  py::class_<Input, TimeFunction, std::shared_ptr<Input>>(m, "Input")
      .def_property_readonly("initial", &Input::initial)
      .def_property_readonly("name", &Input::name);
  m.def("input", &input, py::arg("initial"), py::arg("name") = "");
  m.def(
      "python_function",
      [](py::function f, std::string where, bool derivatives, int component, int components) -> TimeFunctionPtr {
        if (component >= components) throw ModelError(where + ": component " + std::to_string(component) + " of " +
                                                       std::to_string(components));
        return std::make_shared<PythonTimeFunction>(std::move(f), std::move(where), derivatives, component,
                                                    components);
      },
      py::arg("f"), py::arg("where"), py::arg("derivatives"), py::arg("component") = -1, py::arg("components") = 2);
}

}  // namespace lagmb::python
