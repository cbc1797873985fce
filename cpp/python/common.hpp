// What the binding files of lagmb._core share (cpp/python/*.cpp): numpy and
// dict conversions, the options by name, Python callables as time functions
// and their garbage-collector support, Ctrl-C and user-function errors.
// Translation only: no physics here.
#pragma once

#include <pybind11/eigen.h>
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <memory>
#include <optional>

#include "lagmb/interrupt.hpp"
#include "lagmb/lagmb.hpp"

namespace lagmb::python {

namespace py = pybind11;
using namespace lagmb;

/// A numpy array that owns `data` (no copy).
inline py::array_t<double> to_numpy(std::vector<double>&& data, std::vector<py::ssize_t> shape) {
  auto* owner = new std::vector<double>(std::move(data));
  py::capsule free_when_done(owner, [](void* p) { delete static_cast<std::vector<double>*>(p); });
  return py::array_t<double>(shape, owner->data(), free_when_done);
}

inline py::dict to_python(Trajectory&& tr) {
  const py::ssize_t k = tr.size();
  py::dict out;
  out["t"] = to_numpy(std::move(tr.t), {k});
  out["q"] = to_numpy(std::move(tr.q), {k, tr.n});
  out["v"] = to_numpy(std::move(tr.v), {k, tr.n});
  out["a"] = to_numpy(std::move(tr.a), {k, tr.n});
  out["lam"] = to_numpy(std::move(tr.lam), {k, tr.m});
  if (tr.inputs.size() == size_t(k) * size_t(tr.p)) out["inputs"] = to_numpy(std::move(tr.inputs), {k, tr.p});
  if (tr.run_state.size() == size_t(k) * size_t(tr.state_size))
    out["run_state"] = to_numpy(std::move(tr.run_state), {k, tr.state_size});
  py::dict stats;
  tr.stats.for_each_field([&](const char* name, const auto& value) { stats[name] = value; });
  out["stats"] = stats;
  py::list events;
  for (const EventRecord& e : tr.events) {
    py::dict ev;
    ev["t"] = e.t;
    ev["element"] = e.element;
    ev["kind"] = e.kind;
    ev["label"] = e.label;
    ev["speed_before"] = e.speed_before;
    ev["speed_after"] = e.speed_after;
    events.append(ev);
  }
  out["events"] = events;
  out["dropped_rows"] = tr.dropped_rows;
  if (const py::ssize_t count = py::ssize_t(tr.sensitivity_names.size())) {
    const py::ssize_t w = 2 * tr.n + tr.m;
    out["sensitivity_names"] = tr.sensitivity_names;
    const py::ssize_t ks = py::ssize_t(tr.sensitivities.size()) / (count * w);
    out["sensitivities"] = to_numpy(std::move(tr.sensitivities), {ks, count, w});
    out["sensitivity_a"] = to_numpy(std::move(tr.sensitivity_a), {ks, count, tr.n});
  }
  return out;
}

/// SimulationOptions from their fields by name (checked in Python, and
/// again by the run).
inline SimulationOptions options_from(const py::dict& options, const std::string& who) {
  SimulationOptions o;
  size_t used = 0;
  o.for_each_field([&](const char* name, auto& field) {
    using T = std::decay_t<decltype(field)>;
    if (!options.contains(name)) return;
    if constexpr (is_choice_v<T>)
      field = choice_from<T>(options[name].template cast<std::string>());  // the one place a name is parsed
    else
      field = options[name].template cast<T>();
    ++used;
  });
  if (used != options.size())
    for (const auto& item : options) {
      bool known = false;
      o.for_each_field([&](const char* name, auto&) { known = known || py::str(item.first).equal(py::str(name)); });
      if (!known) throw ModelError(who + ": unknown option '" + std::string(py::str(item.first)) + "'");
    }
  return o;
}

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// The outputs Python holds as a core OutputView (no copy): t, and the
/// arrays given (null: not read); `inputs` empty: their initial values;
/// `state` empty: the run state at a run's start.
inline OutputView view_of(const Eigen::VectorXd& t, const RowMajor* q, const RowMajor* v, const RowMajor* lam,
                   const RowMajor& inputs, const RowMajor& state = RowMajor()) {
  OutputView out;
  out.k = int(t.size());
  out.t = t.data();
  out.q = q ? q->data() : nullptr;
  out.v = v ? v->data() : nullptr;
  out.lam = lam ? lam->data() : nullptr;
  out.inputs = inputs.size() ? inputs.data() : nullptr;
  out.state = state.size() ? state.data() : nullptr;
  return out;
}

/// The one check of the arrays a query of a compiled model reads (Model.reaction,
/// effort, energy, mass_matrix, ...), each named in the order the query reads
/// them: q, v and a have a column per coordinate, lam and w one per
/// constraint; at output times t every array has one row per time, and
/// inputs and state (empty: not given) one row per time and a column per
/// input of the model, or per double of its run state (Result.run_state).
///   Given(model, t).coordinates(q, "q").multipliers(lam, "lam").inputs(inputs).state(state);
/// Given(model) checks one state (vectors), or states the query counts itself.
class Given {
 public:
  explicit Given(const Model& model, Eigen::Index states = -1) : model_(model), states_(states) {
    if (!model.finalized()) throw ModelError("the model is not finalized");
  }
  Given(const Model& model, const Eigen::VectorXd& t) : Given(model, t.size()) { t_ = &t; }

  const Given& coordinates(const RowMajor& x, const char* what) const {
    return columns(x.rows(), x.cols(), model_.n_coordinates(), what);
  }
  const Given& coordinates(const Eigen::VectorXd& x, const char* what) const {
    return columns(1, x.size(), model_.n_coordinates(), what);
  }
  const Given& multipliers(const RowMajor& x, const char* what) const {
    return columns(x.rows(), x.cols(), model_.n_constraints(), what);
  }
  const Given& multipliers(const Eigen::VectorXd& x, const char* what) const {
    return columns(1, x.size(), model_.n_constraints(), what);
  }
  /// lam where a query reads it only if given (empty: not).
  const Given& multipliers_if_given(const RowMajor& lam) const { return lam.size() ? multipliers(lam, "lam") : *this; }
  const Given& inputs(const RowMajor& x) const {
    if (x.size() && (x.rows() != states_ || x.cols() != Eigen::Index(model_.inputs().size())))
      throw ModelError("inputs must have one row per output and one column per input of the model (" +
                       std::to_string(model_.inputs().size()) + ")");
    return *this;
  }
  const Given& state(const RowMajor& x) const {
    if (x.size() && (x.rows() != states_ || x.cols() != Eigen::Index(model_.run_state_size())))
      throw ModelError("state must have one row per output and " + std::to_string(model_.run_state_size()) +
                       " columns (the model's run state)");
    return *this;
  }

 private:
  const Given& columns(Eigen::Index rows, Eigen::Index cols, int want, const char* what) const {
    if (cols != want)
      throw ModelError(std::string(what) + " must have " + std::to_string(want) + " columns, got " +
                       std::to_string(cols));
    if (t_ && rows != t_->size())
      throw ModelError(std::string(what) + " has " + std::to_string(rows) + " rows but t has " +
                       std::to_string(t_->size()) + " entries: one row per output time");
    return *this;
  }
  const Model& model_;
  Eigen::Index states_;
  const Eigen::VectorXd* t_ = nullptr;
};

inline py::handle g_simulation_error, g_assembly_error, g_user_function_error;

/// A Python exception kept across C++ frames; released with the GIL.
inline std::shared_ptr<void> hold(py::object value) {
  return std::shared_ptr<void>(new py::object(std::move(value)), [](void* p) {
    py::gil_scoped_acquire gil;
    delete static_cast<py::object*>(p);
  });
}

/// The exception a user function raised in this thread's current call: the
/// cause of the SimulationError it leads to (chained as __cause__). Per
/// thread because the error crosses the core as a C++ exception that
/// carries only text; the model's evaluation never reads it.
inline thread_local std::shared_ptr<void> t_pending_cause;

/// For one call from Python into the core: Ctrl-C is honoured at the core's
/// poll points (as Interrupted, which carries the KeyboardInterrupt back),
/// and a cause left by an earlier call is forgotten.
struct PythonCall {
  PythonCall()
      : interrupts([] {
          py::gil_scoped_acquire gil;
          if (PyErr_CheckSignals() != 0) {
            py::error_already_set e;
            Interrupted stop;
            stop.cause = hold(e.value());
            throw stop;
          }
        }) {
    t_pending_cause.reset();
  }
  InterruptScope interrupts;
};

/// A Python callable as a time function. Called with the GIL taken (the run
/// releases it); a Python exception or a bad return value becomes a
/// UserFunctionError naming the element (the exception kept as its cause),
/// so nothing unwinds through SUNDIALS and the run stops with
/// SimulationError. KeyboardInterrupt and SystemExit are the user's: they
/// stop the run as Interrupted and come back unchanged.
///
/// Each instance owns one reference to its callable, and each instance has
/// one owner that Python's garbage collector can see (a TimeFunction
/// object, or the Model it was cloned into), so a callable that refers to
/// its own model forms a cycle the collector can break.
class PythonTimeFunction final : public TimeFunction {
 public:
  /// component: -1 for f(t) -> (y, dy, ddy) (derivatives) or f(t) -> y;
  /// 0, 1 (or 2) for an entry of f(t) -> (fx, fy) (or (fx, fy, fz):
  /// components = 3).
  PythonTimeFunction(py::object f, std::string where, bool derivatives, int component, int components = 2)
      : f_(std::move(f)),
        where_(std::move(where)),
        derivatives_(derivatives),
        component_(component),
        components_(components) {}
  ~PythonTimeFunction() override {
    py::gil_scoped_acquire gil;
    f_ = py::object();
  }
  /// Another instance with its own reference (for a new owner).
  std::shared_ptr<PythonTimeFunction> clone() const {
    py::gil_scoped_acquire gil;
    return std::make_shared<PythonTimeFunction>(f_, where_, derivatives_, component_, components_);
  }
  PyObject* callable() const { return f_.ptr(); }
  /// What it takes of the callable: -1 all of it, else that entry of its result.
  int component() const { return component_; }
  /// Drops the reference (the garbage collector breaking a cycle).
  void clear() { f_ = py::none(); }

  TimeValue eval(double t) const override {
    py::gil_scoped_acquire gil;
    TimeValue v;
    py::object r;
    try {
      r = f_(t);
      if (derivatives_) {
        auto seq = r.cast<std::vector<double>>();
        if (seq.size() != 3) throw py::value_error("must return (y, dy, ddy)");
        v = {seq[0], seq[1], seq[2]};
      } else if (component_ >= 0) {
        auto seq = r.cast<std::vector<double>>();
        if (int(seq.size()) != components_)
          throw py::value_error(components_ == 2 ? "must return (fx, fy)" : "must return (x, y, z)");
        v.f = seq[component_];
      } else {
        v.f = r.cast<double>();
      }
    } catch (py::error_already_set& e) {
      if (!e.matches(PyExc_Exception)) {  // KeyboardInterrupt, SystemExit: pass them on
        Interrupted stop;
        stop.cause = hold(e.value());
        stop.t = t;
        throw stop;
      }
      t_pending_cause = hold(e.value());
      // type and message only: the run's error should read as one line
      const std::string type = py::str(e.type().attr("__name__"));
      const std::string text = py::str(e.value());
      throw UserFunctionError(where_ + " raised " + type + ": " + text + " (at t = " + std::to_string(t) + ")");
    } catch (const py::cast_error&) {  // its message names no Python type ('?')
      const std::string wanted = derivatives_    ? "(y, dy, ddy), three numbers"
                                 : component_ < 0 ? "a number"
                                 : components_ == 2 ? "(fx, fy), two numbers"
                                                    : "(x, y, z), three numbers";
      std::string got = "an object", shown;
      try {
        got = py::str(py::type::of(r).attr("__name__"));
        shown = py::repr(r);
        if (shown.size() > 60) shown = shown.substr(0, 57) + "...";
      } catch (py::error_already_set&) {  // a repr that fails: the type is enough
      }
      throw UserFunctionError(where_ + ": the function must return " + wanted + ", got " + got + " " + shown +
                              " (at t = " + std::to_string(t) + ")");
    } catch (const std::exception& e) {
      throw UserFunctionError(where_ + ": the function " + e.what() + " (at t = " + std::to_string(t) + ")");
    }
    if (!std::isfinite(v.f) || !std::isfinite(v.df) || !std::isfinite(v.ddf))
      throw UserFunctionError(where_ + " returned a non-finite value at t = " + std::to_string(t));
    return v;
  }

 private:
  py::object f_;
  std::string where_;
  bool derivatives_;
  int component_, components_;
};

/// The function a Model keeps: a Python function is cloned, so that the
/// Model owns its reference alone (see PythonTimeFunction).
inline TimeFunctionPtr own(const TimeFunctionPtr& f) {
  if (auto* p = dynamic_cast<PythonTimeFunction*>(f.get())) return p->clone();
  return f;
}

/// tp_traverse / tp_clear for a class whose C++ object owns Python
/// functions: `Each::each(self, visit)` calls visit(PythonTimeFunction&) for
/// each, `Each::clear(self)` lets them go.
template <class T, class Each>
inline void collectable(PyHeapTypeObject* heap_type) {
  auto* type = &heap_type->ht_type;
  type->tp_flags |= Py_TPFLAGS_HAVE_GC;
  type->tp_traverse = [](PyObject* self, visitproc visit, void* arg) -> int {
    Py_VISIT(Py_TYPE(self));
    if (!py::detail::is_holder_constructed(self)) return 0;
    int out = 0;
    Each::each(py::cast<T&>(py::handle(self)), [&](PythonTimeFunction& f) {
      if (!out && f.callable()) out = visit(f.callable(), arg);
    });
    return out;
  };
  type->tp_clear = [](PyObject* self) -> int {
    if (py::detail::is_holder_constructed(self)) Each::clear(py::cast<T&>(py::handle(self)));
    return 0;
  };
}

template <class Visit>
inline void each_python_function(const TimeFunctionPtr& f, Visit&& visit) {
  if (auto* p = dynamic_cast<PythonTimeFunction*>(f.get())) visit(*p);
}

/// The Python functions a spec or a compiled model holds. Each Python
/// object reports the references it owns, once: a spec those of its elements
/// (its draft model, no Python object, shares them), a compiled model its own
/// (the binding builds each with own(), a new reference to every callable,
/// and never shares one between Python objects). A reference reported by an
/// object that does not own it would let the collector clear a callable
/// still in use.
struct SpecFunctions {
  template <class Visit>
  static void each(const ModelSpec& spec, Visit&& visit) {
    for (const ModelSpec::Element& e : spec.elements())
      for (const auto& [key, value] : e.args.values()) {
        if (const auto* f = std::get_if<TimeFunctionPtr>(&value)) each_python_function(*f, visit);
        if (const auto* fs = std::get_if<std::pair<TimeFunctionPtr, TimeFunctionPtr>>(&value)) {
          each_python_function(fs->first, visit);
          each_python_function(fs->second, visit);
        }
        if (const auto* f3 = std::get_if<std::array<TimeFunctionPtr, 3>>(&value))
          for (const TimeFunctionPtr& f : *f3) each_python_function(f, visit);
      }
  }
  static void clear(ModelSpec& spec) {
    each(spec, [](PythonTimeFunction& f) { f.clear(); });
  }
};

struct ModelFunctions {
  template <class Visit>
  static void each(const Model& model, Visit&& visit) {
    for (const auto& f : model.time_functions()) each_python_function(f, visit);
  }
  static void clear(Model& model) {
    each(model, [](PythonTimeFunction& f) { f.clear(); });
  }
};

struct OwnFunction {
  template <class Visit>
  static void each(TimeFunction& f, Visit&& visit) {
    if (auto* p = dynamic_cast<PythonTimeFunction*>(&f)) visit(*p);
  }
  static void clear(TimeFunction& f) {
    each(f, [](PythonTimeFunction& p) { p.clear(); });
  }
};

/// The parts of the module, one per file: what each binds.
void bind_errors(py::module_& m);     // module.cpp: exceptions and their translation
void bind_functions(py::module_& m);  // functions.cpp: time functions and inputs
void bind_model(py::module_& m);      // model.cpp: ModelSpec, compiled Model, the registry

/// The compiled Model's queries, by what they answer (model_queries.cpp).
using ModelClass = py::class_<Model, std::shared_ptr<Model>>;
void bind_model_structure(ModelClass& model);  // sizes, names, inputs, parameters, what each element is
void bind_model_readings(ModelClass& model);   // at a run's outputs: reactions, efforts, contacts, energy, ...
void bind_model_terms(ModelClass& model);      // the equations' terms at one state: Phi_q, M, gamma, Q, ...
/// Where elements attach to a body: [(x, y)] or [(x, y, z)] (Model::outline).
py::list outline_of(const Model& model, int body);
/// Where an element attaches: [(body index, x, y[, z])] (Model::attachments).
py::list attachments_of(const Model& model, const std::string& element);
void bind_runs(py::module_& m);       // runs.cpp: simulate, Simulator, one-instant solves, methods, options
void bind_fmu(py::module_& m);        // fmu.cpp: the co-simulation behind an FMU
void bind_statics(py::module_& m);    // statics.cpp: equilibrium, degrees of freedom

}  // namespace lagmb::python
