// lagmb._core: the co-simulation an FMU runs.
#include "common.hpp"

namespace lagmb::python {

void bind_fmu(py::module_& m) {
  m.def(
      "cosimulation_setup",
      [](const ModelSpec& spec, const py::dict& options, std::vector<std::string> reactions,
         std::vector<std::string> efforts) {
        CoSimulationSetup setup;
        setup.model = spec.to_text();
        setup.options = options_from(options, "fmu");
        setup.reactions = std::move(reactions);
        setup.efforts = std::move(efforts);
        return setup.to_text();
      },
      py::arg("spec"), py::arg("options"), py::arg("reactions"), py::arg("efforts"),
      "The text an FMU carries (CoSimulationSetup::to_text): the model, its options, its outputs.");
  py::class_<CoSimulation>(m, "CoSimulation")
      .def(py::init([](const std::string& setup) {
             return std::make_unique<CoSimulation>(CoSimulationSetup::from_text(setup));
           }),
           py::arg("setup"))
      .def_property_readonly("variables",
                             [](const CoSimulation& c) {
                               py::list out;
                               for (const CoVariable& v : c.variables()) {
                                 py::dict d;
                                 d["name"] = v.name;
                                 d["causality"] = v.causality;
                                 d["variability"] = v.variability;
                                 d["unit"] = v.unit;
                                 d["description"] = v.description;
                                 d["start"] = v.start;
                                 out.append(d);
                               }
                               return out;
                             })
      .def("set", &CoSimulation::set, py::arg("value_reference"), py::arg("value"))
      .def("get",
           [](CoSimulation& c, size_t vr) {
             PythonCall call;
             return c.get(vr);
           })
      .def("enter_initialization", &CoSimulation::enter_initialization, py::arg("t0"), py::arg("tolerance") = 0.0)
      .def("exit_initialization",
           [](CoSimulation& c) {
             PythonCall call;
             c.exit_initialization();
           })
      .def("do_step",
           [](CoSimulation& c, double t, double h) {
             PythonCall call;
             py::gil_scoped_release release;
             c.do_step(t, h);
           })
      .def("reset", &CoSimulation::reset);
}

}  // namespace lagmb::python
