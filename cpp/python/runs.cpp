// lagmb._core: runs: simulate, the Simulator, one-instant solves, the methods, the options.
#include "common.hpp"

namespace lagmb::python {

void bind_runs(py::module_& m) {
  m.def(
      "assemble",
      [](const Model& model, double t) {
        PythonCall call;
        ConsistentState s = assemble(model, t);
        return py::make_tuple(s.q, s.v, s.qdd, s.lam, s.dropped_rows);
      },
      py::arg("model"), py::arg("t") = 0.0,
      "Consistent (q, v, qdd, lam, dropped rows) at time t from the model's initial values.");

  m.def(
      "solve_accelerations",
      [](const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& v, double t) {
        PythonCall call;
        Eigen::VectorXd qdd, lam;
        solve_accelerations(model, q, v, t, qdd, lam);
        return py::make_tuple(qdd, lam);
      },
      py::arg("model"), py::arg("q"), py::arg("v"), py::arg("t") = 0.0);

  m.def(
      "choices",
      [] {
        py::dict out;
        auto names = [](auto choice) {
          py::list l;
          for (const auto& [value, name] : ChoiceNames<decltype(choice)>::names)
            if (*name) l.append(name);
          return py::tuple(l);
        };
        out["analysis"] = names(Analysis{});
        out["start"] = names(Start{});
        out["formulation"] = names(Formulation{});
        out["integrator"] = names(Integrator{});
        return out;
      },
      "The names of each choice of SimulationOptions (lagmb/options.hpp), in order.");

  m.def(
      "default_options",
      [] {
        py::dict out;
        SimulationOptions o;
        o.for_each_field([&](const char* name, const auto& value) {
          using T = std::decay_t<decltype(value)>;
          if constexpr (is_choice_v<T>)
            out[name] = name_of(value);
          else
            out[name] = value;
        });
        return out;
      },
      "SimulationOptions' defaults by field name (the choices by their names): what every run takes by default.");

  m.def(
      "methods",
      [] {
        py::list out;
        for (const Method& x : methods()) {
          py::dict d;
          x.for_each_field([&](const char* name, const auto& value) { d[name] = value; });
          out.append(d);
        }
        return out;
      },
      "The integration methods (lagmb/integrators/methods.hpp), one dict each, the default first.");

  m.def(
      "simulate",
      [](const Model& model, const py::dict& options, py::object progress,
         const std::vector<std::string>& sensitivities) {
        SimulationOptions o = options_from(options, "simulate");
        // between steps: let Ctrl-C through, and report progress if asked
        // (a borrowed pointer: the std::function is copied without the GIL)
        PyObject* report = progress.ptr();
        if (report != Py_None)
          o.progress = [report](double t) {
            py::gil_scoped_acquire gil;
            try {
              py::handle{report}(t);
            } catch (py::error_already_set& e) {
              if (!e.matches(PyExc_Exception)) {  // KeyboardInterrupt, SystemExit: the user's
                Interrupted stop;
                stop.cause = hold(e.value());
                throw stop;
              }
              t_pending_cause = hold(e.value());
              throw UserFunctionError("progress raised " + std::string(py::str(e.type().attr("__name__"))) + ": " +
                                      std::string(py::str(e.value())) + " (at t = " + std::to_string(t) + ")");
            }
          };
        PythonCall call;
        Trajectory tr;
        {
          py::gil_scoped_release release;
          tr = simulate(model, o, {}, sensitivities);
        }
        return to_python(std::move(tr));
      },
      py::arg("model"), py::arg("options"), py::arg("progress") = py::none(),
      py::arg("sensitivities") = std::vector<std::string>{},
      "Runs simulate(model, options): options by the names of SimulationOptions' fields.");

  py::class_<SimulatorState>(m, "SimulatorState")
      .def_property_readonly("t", [](const SimulatorState& s) { return s.t; })
      .def_property_readonly("q", [](const SimulatorState& s) { return Eigen::VectorXd(s.q); })
      .def_property_readonly("v", [](const SimulatorState& s) { return Eigen::VectorXd(s.v); })
      .def_property_readonly("inputs", [](const SimulatorState& s) { return Eigen::VectorXd(s.inputs); })
      .def("__copy__", [](const SimulatorState& s) { return s; })
      .def("__deepcopy__", [](const SimulatorState& s, const py::dict&) { return s; }, py::arg("memo"))
      .def("__reduce__", [](const SimulatorState&) -> py::tuple {
        throw ModelError(
            "a SimulatorState cannot be pickled: it belongs to its model's simulators in this process. To carry a "
            "run elsewhere, pickle the Model and the state's t, q, v and inputs, and start a Simulator there "
            "from them (set the model's initial state, or advance a new simulator to t)");
      });

  // the model is kept alive by the simulator's Python object (keep_alive).
  // A Simulator takes one call at a time (simulator.hpp): every call waits
  // for it without the GIL, so that the call in progress can call Python.
  using Release = py::call_guard<py::gil_scoped_release>;
  py::class_<Simulator>(m, "Simulator")
      .def(py::init([](const Model& model, const py::dict& options, double output_interval) {
             SimulationOptions o = options_from(options, "Simulator");
             PythonCall call;
             py::gil_scoped_release release;
             return std::make_unique<Simulator>(model, o, output_interval);
           }),
           py::arg("model"), py::arg("options"), py::arg("output_interval") = 0.0, py::keep_alive<1, 2>())
      .def_property_readonly("t", py::cpp_function(&Simulator::t, Release()))
      .def_property_readonly("q", py::cpp_function(&Simulator::q, Release()))
      .def_property_readonly("v", py::cpp_function(&Simulator::v, Release()))
      .def_property_readonly("a", py::cpp_function(
                                      [](Simulator& s) {
                                        PythonCall call;
                                        py::gil_scoped_release release;
                                        return s.a();
                                      }))
      .def_property_readonly("lam", py::cpp_function(
                                        [](Simulator& s) {
                                          PythonCall call;
                                          py::gil_scoped_release release;
                                          return s.lam();
                                        }))
      .def(
          "advance",
          [](Simulator& s, double t) {
            PythonCall call;
            py::gil_scoped_release release;
            s.advance(t);
          },
          py::arg("t"))
      .def("set_input", &Simulator::set_input, py::arg("name"), py::arg("value"), Release())
      .def(
          "set_inputs",
          [](Simulator& s, const std::vector<std::string>& names, const std::vector<double>& values) {
            if (names.size() != values.size()) throw ModelError("set_inputs: one value per name");
            py::gil_scoped_release release;
            for (size_t k = 0; k < names.size(); ++k) s.set_input(names[k], values[k]);
          },
          py::arg("names"), py::arg("values"), "set_input for each (name, value), in one call")
      .def("input", &Simulator::input, py::arg("name"), Release())
      .def_property_readonly("inputs", py::cpp_function(&Simulator::inputs, Release()))
      .def_property_readonly("run_state", py::cpp_function(&Simulator::run_state, Release()))
      .def("state", &Simulator::state, Release())
      .def(
          "set_state",
          [](Simulator& s, const SimulatorState& state) {
            PythonCall call;
            py::gil_scoped_release release;
            s.set_state(state);
          },
          py::arg("state"))
      .def("result",
           [](const Simulator& s) {
             Trajectory tr;
             {
               py::gil_scoped_release release;
               tr = s.result();
             }
             return to_python(std::move(tr));
           })
      .def_property_readonly("stats",
                             [](const Simulator& s) {
                               Stats now;
                               {
                                 py::gil_scoped_release release;
                                 now = s.stats();
                               }
                               py::dict stats;
                               now.for_each_field([&](const char* name, const auto& value) { stats[name] = value; });
                               return stats;
                             })
      .def_property_readonly("failure", py::cpp_function(&Simulator::failure, Release()));
}

}  // namespace lagmb::python
