// lagmb._core: translation only. numpy in and out, C++ errors to Python errors.
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

namespace py = pybind11;
using namespace lagmb;

namespace {

/// A numpy array that owns `data` (no copy).
py::array_t<double> to_numpy(std::vector<double>&& data, std::vector<py::ssize_t> shape) {
  auto* owner = new std::vector<double>(std::move(data));
  py::capsule free_when_done(owner, [](void* p) { delete static_cast<std::vector<double>*>(p); });
  return py::array_t<double>(shape, owner->data(), free_when_done);
}

py::dict to_python(Trajectory&& tr) {
  const py::ssize_t k = tr.size();
  py::dict out;
  out["t"] = to_numpy(std::move(tr.t), {k});
  out["q"] = to_numpy(std::move(tr.q), {k, tr.n});
  out["v"] = to_numpy(std::move(tr.v), {k, tr.n});
  out["a"] = to_numpy(std::move(tr.a), {k, tr.n});
  out["lam"] = to_numpy(std::move(tr.lam), {k, tr.m});
  if (tr.inputs.size() == size_t(k) * size_t(tr.p)) out["inputs"] = to_numpy(std::move(tr.inputs), {k, tr.p});
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
  return out;
}

/// SimulationOptions from their fields by name (checked in Python, and
/// again by the run).
SimulationOptions options_from(const py::dict& options, const std::string& who) {
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

void require_inputs(const Model& model, const RowMajor& inputs, Eigen::Index outputs) {
  if (inputs.size() && (inputs.rows() != outputs || inputs.cols() != Eigen::Index(model.inputs().size())))
    throw ModelError("inputs must have one row per output and one column per input of the model (" +
                     std::to_string(model.inputs().size()) + ")");
}

/// The outputs Python holds as a core OutputView (no copy): t, and the
/// arrays given (null: not read); `inputs` empty: their initial values.
OutputView view_of(const Eigen::VectorXd& t, const RowMajor* q, const RowMajor* v, const RowMajor* lam,
                   const RowMajor& inputs) {
  OutputView out;
  out.k = int(t.size());
  out.t = t.data();
  out.q = q ? q->data() : nullptr;
  out.v = v ? v->data() : nullptr;
  out.lam = lam ? lam->data() : nullptr;
  out.inputs = inputs.size() ? inputs.data() : nullptr;
  return out;
}

void require_rows(const Model& model, const RowMajor& x, int cols, const char* what) {
  if (!model.finalized()) throw ModelError("the model is not finalized");
  if (x.cols() != cols)
    throw ModelError(std::string(what) + " must have " + std::to_string(cols) + " columns, got " +
                     std::to_string(x.cols()));
}

/// Per-output arrays must all have one row per output time.
void require_outputs(const Eigen::VectorXd& t, std::initializer_list<std::pair<const RowMajor*, const char*>> arrays) {
  for (const auto& [x, what] : arrays)
    if (x->rows() != t.size())
      throw ModelError(std::string(what) + " has " + std::to_string(x->rows()) + " rows but t has " +
                       std::to_string(t.size()) + " entries: one row per output time");
}

py::handle g_simulation_error, g_assembly_error, g_user_function_error;

/// A Python exception kept across C++ frames; released with the GIL.
std::shared_ptr<void> hold(py::object value) {
  return std::shared_ptr<void>(new py::object(std::move(value)), [](void* p) {
    py::gil_scoped_acquire gil;
    delete static_cast<py::object*>(p);
  });
}

/// The exception a user function raised in this thread's current call: the
/// cause of the SimulationError it leads to (chained as __cause__).
thread_local std::shared_ptr<void> t_pending_cause;

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
TimeFunctionPtr own(const TimeFunctionPtr& f) {
  if (auto* p = dynamic_cast<PythonTimeFunction*>(f.get())) return p->clone();
  return f;
}

/// tp_traverse / tp_clear for a class whose C++ object owns Python
/// functions: `Each::each(self, visit)` calls visit(PythonTimeFunction&) for
/// each, `Each::clear(self)` lets them go.
template <class T, class Each>
void collectable(PyHeapTypeObject* heap_type) {
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
void each_python_function(const TimeFunctionPtr& f, Visit&& visit) {
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

/// A point as Python has it: (x, y) in a planar model, (x, y, z) in a spatial one.
py::tuple point_of(const Model& model, const Vec3& p) {
  if (model.dimension() == 2) return py::make_tuple(p.x(), p.y());
  return py::make_tuple(p.x(), p.y(), p.z());
}

/// [(x, y)] or [(x, y, z)]: where elements attach to a body (Model::outline).
py::list outline_of(const Model& model, int body) {
  py::list out;
  for (const Vec3& p : model.outline(body)) out.append(point_of(model, p));
  return out;
}

/// [(body index, x, y[, z])]: where an element attaches (Model::attachments).
py::list attachments_of(const Model& model, const std::string& element) {
  py::list out;
  for (const auto& [body, p] : model.attachments(element))
    out.append(py::tuple(py::make_tuple(body) + point_of(model, p)));
  return out;
}

/// A Python value (already checked by lagmb.model) as the registry's Value.
Value to_value(const KindInfo& kind, const std::string& key, py::handle x) {
  const Param* p = kind.param(key);
  if (!p) throw ModelError(kind.name + " has no parameter '" + key + "'");
  if (x.is_none()) return std::monostate{};
  switch (p->type) {
    case ParamType::kText:
    case ParamType::kJoint:
    case ParamType::kChoice: return x.cast<std::string>();
    case ParamType::kReal: return x.cast<double>();
    case ParamType::kVec2: return x.cast<Vec2>();
    case ParamType::kBool: return x.cast<bool>();
    case ParamType::kBody: return BodyIndex{x.cast<int>()};
    case ParamType::kMotion:
    case ParamType::kFunction: return own(x.cast<TimeFunctionPtr>());
    case ParamType::kFunctionPair: {
      auto pair = x.cast<std::pair<TimeFunctionPtr, TimeFunctionPtr>>();
      return std::make_pair(own(pair.first), own(pair.second));
    }
    case ParamType::kVec3: return x.cast<Vec3>();
    case ParamType::kFunctionTriple: {
      auto fs = x.cast<std::array<TimeFunctionPtr, 3>>();
      return std::array<TimeFunctionPtr, 3>{own(fs[0]), own(fs[1]), own(fs[2])};
    }
    case ParamType::kOrientation:  // (w, x, y, z), or a 3 x 3 matrix (lagmb.model gives nested tuples)
      if (py::len(x) == 4) return x.cast<Vec4>();
      return x.cast<Mat3>();
    case ParamType::kInertia:
      if (py::len(x) == 3 && !py::isinstance<py::sequence>(py::reinterpret_borrow<py::sequence>(x)[0]))
        return x.cast<Vec3>();
      return x.cast<Mat3>();
  }
  return std::monostate{};
}

/// A default (a number, a vector, a flag or None) as Python has it.
py::object default_to_python(const Value& v) {
  if (const double* x = std::get_if<double>(&v)) return py::float_(*x);
  if (const Vec2* x = std::get_if<Vec2>(&v)) return py::make_tuple(x->x(), x->y());
  if (const Vec3* x = std::get_if<Vec3>(&v)) return py::make_tuple(x->x(), x->y(), x->z());
  if (const Vec4* x = std::get_if<Vec4>(&v)) return py::make_tuple((*x)[0], (*x)[1], (*x)[2], (*x)[3]);
  if (const bool* x = std::get_if<bool>(&v)) return py::bool_(*x);
  if (const std::string* x = std::get_if<std::string>(&v)) return py::str(*x);
  return py::none();
}

const char* type_name(ParamType type) {
  switch (type) {
    case ParamType::kText: return "text";
    case ParamType::kReal: return "real";
    case ParamType::kVec2: return "vec2";
    case ParamType::kBool: return "bool";
    case ParamType::kBody: return "body";
    case ParamType::kJoint: return "joint";
    case ParamType::kChoice: return "choice";
    case ParamType::kMotion: return "motion";
    case ParamType::kFunction: return "function";
    case ParamType::kFunctionPair: return "function_pair";
    case ParamType::kVec3: return "vec3";
    case ParamType::kOrientation: return "orientation";
    case ParamType::kInertia: return "inertia";
    case ParamType::kFunctionTriple: return "function_triple";
  }
  return "?";
}

/// The registry as plain Python data (lagmb.registry reads it).
py::list kinds_to_python() {
  py::list out;
  for (const KindInfo& k : element_kinds()) {
    py::list params;
    for (const Param& p : k.params) {
      py::dict d;
      d["name"] = p.name;
      d["type"] = type_name(p.type);
      d["required"] = p.required;
      d["default"] = default_to_python(p.fallback);
      d["unit"] = p.unit;
      d["doc"] = p.doc;
      d["choices"] = py::tuple(py::cast(p.choices));
      d["on"] = py::tuple(py::cast(p.on));
      d["local"] = p.local;
      d["keyword_only"] = p.keyword_only;
      d["scene_key"] = p.scene_key.empty() ? p.name : p.scene_key;
      params.append(d);
    }
    py::dict d;
    d["name"] = k.name;
    d["method"] = k.method;
    d["table"] = k.table;
    d["type"] = k.type.empty() ? py::object(py::none()) : py::object(py::str(k.type));
    d["role"] = role_name(k.role);
    d["doc"] = k.doc;
    d["params"] = params;
    d["dimension"] = k.dimension;
    out.append(d);
  }
  return out;
}

}  // namespace

PYBIND11_MODULE(_core, m) {
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

  py::class_<ModelSpec>(m, "ModelSpec", py::custom_type_setup(collectable<ModelSpec, SpecFunctions>))
      .def(py::init<int>(), py::arg("dimension") = 2)
      .def("__copy__", [](const ModelSpec& spec) { return spec.copied(own); })
      .def("__len__", [](const ModelSpec& spec) { return spec.elements().size(); })
      .def_property_readonly("dimension", &ModelSpec::dimension)
      .def("to_text", &ModelSpec::to_text)
      .def_static("from_text", &ModelSpec::from_text, py::arg("text"))
      .def(
          "set_gravity",
          [](ModelSpec& spec, const Eigen::VectorXd& g) {
            if (g.size() == 2) return spec.set_gravity(Vec2(g[0], g[1]));
            if (g.size() == 3) return spec.set_gravity(Vec3(g[0], g[1], g[2]));
            throw ModelError("gravity must have 2 (planar) or 3 (spatial) components, got " + std::to_string(g.size()));
          },
          py::arg("g"))
      .def(
          "add",
          [](ModelSpec& spec, const std::string& kind_name, const std::string& name, const py::dict& values) {
            const KindInfo& kind = find_kind(kind_name);
            Args args(kind);
            for (auto item : values) {
              const std::string key = py::str(item.first);
              args.set(key, to_value(kind, key, item.second));
            }
            spec.add(name, std::move(args));
          },
          py::arg("kind"), py::arg("name"), py::arg("values"))
      .def("compile", [](const ModelSpec& spec) { return spec.build(own); },
           "A new compiled Model with its own references to the Python callables (lagmb.Model keeps it "
           "until the model changes).")
      .def(
          "outline",
          [](const ModelSpec& spec, int body) { return outline_of(spec.draft(), body); },
          py::arg("body"))
      .def(
          "attachments",
          [](const ModelSpec& spec, const std::string& element) { return attachments_of(spec.draft(), element); },
          py::arg("element"));

  // compiled models come from ModelSpec.compile(); nothing here changes one
  py::class_<Model, std::shared_ptr<Model>>(m, "Model", py::custom_type_setup(collectable<Model, ModelFunctions>))
      .def("outline", &outline_of, py::arg("body"))
      .def("attachments", &attachments_of, py::arg("element"))
      .def_property_readonly("finalized", &Model::finalized)
      .def_property_readonly("n_coordinates", &Model::n_coordinates)
      .def_property_readonly("n_constraints", &Model::n_constraints)
      .def_property_readonly("dimension", &Model::dimension)
      .def_property_readonly("inputs",
                             [](const Model& model) {
                               py::list out;
                               for (const InputInfo& in : model.inputs()) {
                                 py::dict d;
                                 d["name"] = in.name;
                                 d["element"] = in.element;
                                 d["parameter"] = in.parameter;
                                 d["unit"] = in.unit;
                                 d["initial"] = in.initial;
                                 out.append(d);
                               }
                               return out;
                             })
      .def_property_readonly("parameters",
                             [](const Model& model) {
                               py::list out;
                               for (const ParameterInfo& p : parameters(model)) {
                                 py::dict d;
                                 d["name"] = p.name;
                                 d["element"] = p.element;
                                 d["key"] = p.key;
                                 d["component"] = p.component;
                                 d["unit"] = p.unit;
                                 d["doc"] = p.doc;
                                 d["value"] = p.value;
                                 out.append(d);
                               }
                               return out;
                             })
      .def(
          "with_parameters",
          [](const Model& model, const ParameterValues& values) -> std::shared_ptr<Model> {
            return with_parameters(model, values, own);
          },
          py::arg("values"),
          "This model built with other parameter values (a new compiled Model; None for no values).")
      .def("constraint_name_of_row", &Model::constraint_name_of_row, py::arg("row"))
      .def("has", &Model::has)
      .def("body_coordinates",
           [](const Model& model, const std::string& name) {
             const ElementRef& r = model.find(name);
             if (r.type != ElementRef::kBody) throw ModelError("'" + name + "' is not a body");
             const Body& b = model.body(r.group);
             return py::make_tuple(b.first_coord, b.n_coordinates());
           })
      .def("constraint_rows",
           [](const Model& model, const std::string& name) {
             const ElementRef& r = model.find(name);
             if (r.type != ElementRef::kConstraint) throw ModelError("'" + name + "' is not a joint or driver");
             const auto& g = *model.constraint_groups()[r.group];
             return py::make_tuple(g.placement(r.index).row0, g.rows(r.index));
           })
      .def("element_kind",
           [](const Model& model, const std::string& name) -> std::string {
             const ElementRef& r = model.find(name);
             if (r.type == ElementRef::kBody) return "body";
             if (r.type == ElementRef::kConstraint) return model.constraint_groups()[r.group]->kind();
             if (r.type == ElementRef::kFriction) return model.friction_groups()[r.group]->kind();
             if (r.type == ElementRef::kEvent) return model.event_groups()[r.group]->kind();
             return model.force_groups()[r.group]->kind();
           })
      .def("initial_state",
           [](const Model& model) { return py::make_tuple(model.initial_q(), model.initial_v()); })
      .def(
          "reaction",
          [](const Model& model, const std::string& name, const Eigen::VectorXd& t, const RowMajor& q,
             const RowMajor& lam, bool joint_axes, const RowMajor& inputs) {
            require_rows(model, q, model.n_coordinates(), "q");
            require_rows(model, lam, model.n_constraints(), "lam");
            require_outputs(t, {{&q, "q"}, {&lam, "lam"}});
            require_inputs(model, inputs, q.rows());
            return reactions(model, name, view_of(t, &q, nullptr, &lam, inputs), joint_axes);
          },
          py::arg("name"), py::arg("t"), py::arg("q"), py::arg("lam"), py::arg("joint_axes") = false,
          py::arg("inputs") = RowMajor(),
          "Force and torque about the centre of mass that the element applies to its second body\n"
          "((x, y) and the torque in the plane, (x, y, z) and (x, y, z) in space); with joint_axes,\n"
          "in the element's own axes.")
      .def(
          "friction",
          [](const Model& model, const std::string& name, const RowMajor& q, const RowMajor& v,
             const RowMajor& lam) {
            require_rows(model, q, model.n_coordinates(), "q");
            require_rows(model, v, model.n_coordinates(), "v");
            require_rows(model, lam, model.n_constraints(), "lam");
            if (v.rows() != q.rows() || lam.rows() != q.rows())
              throw ModelError("q, v and lam must have one row per output (got " + std::to_string(q.rows()) + ", " +
                               std::to_string(v.rows()) + " and " + std::to_string(lam.rows()) + ")");
            const Eigen::VectorXd t = Eigen::VectorXd::Zero(q.rows());  // (friction does not depend on t)
            return friction(model, name, view_of(t, &q, &v, &lam, RowMajor()));
          },
          py::arg("name"), py::arg("q"), py::arg("v"), py::arg("lam"),
          "(friction torque or force on the joint's second body, slip rate) at each state")
      .def(
          "friction_forces",
          [](const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& v, const Eigen::VectorXd& lam) {
            require_rows(model, q.transpose(), model.n_coordinates(), "q");
            require_rows(model, v.transpose(), model.n_coordinates(), "v");
            require_rows(model, lam.transpose(), model.n_constraints(), "lam");
            Data d(model);
            d.Q.setZero();
            add_friction_forces(model, d, q.data(), v.data(), lam.data());
            assemble_friction_derivatives(model, d, q.data(), v.data(), lam.data());
            const Eigen::Index n = q.size(), m = lam.size();
            Eigen::MatrixXd Qq = Eigen::MatrixXd::Zero(n, n), Qv = Qq, Ql = Eigen::MatrixXd::Zero(n, m);
            if (!model.friction_groups().empty()) {
              Qq = Eigen::MatrixXd(d.friction_Q_q);
              Qv = Eigen::MatrixXd(d.friction_Q_v);
              Ql = Eigen::MatrixXd(d.friction_Q_lam).transpose();
            }
            return py::make_tuple(d.Q, Qq, Qv, Ql);
          },
          py::arg("q"), py::arg("v"), py::arg("lam"), "(Q_f, dQ_f/dq, dQ_f/dv, dQ_f/dlam) of joint friction")
      .def(
          "energy",
          [](const Model& model, const Eigen::VectorXd& t, const RowMajor& q, const RowMajor& v,
             const RowMajor& inputs) {
            require_rows(model, q, model.n_coordinates(), "q");
            require_rows(model, v, model.n_coordinates(), "v");
            require_outputs(t, {{&q, "q"}, {&v, "v"}});
            require_inputs(model, inputs, q.rows());
            return energy(model, view_of(t, &q, &v, nullptr, inputs));
          },
          py::arg("t"), py::arg("q"), py::arg("v"), py::arg("inputs") = RowMajor())
      .def(
          "residual",
          [](const Model& model, const Eigen::VectorXd& t, const RowMajor& q, const RowMajor& inputs) {
            require_rows(model, q, model.n_coordinates(), "q");
            require_outputs(t, {{&q, "q"}});
            require_inputs(model, inputs, q.rows());
            return constraint_residual(model, view_of(t, &q, nullptr, nullptr, inputs));
          },
          py::arg("t"), py::arg("q"), py::arg("inputs") = RowMajor(), "max |Phi| at each state")
      .def(
          "velocity_residual",
          [](const Model& model, const Eigen::VectorXd& t, const RowMajor& q, const RowMajor& v,
             const RowMajor& inputs) {
            require_rows(model, q, model.n_coordinates(), "q");
            require_rows(model, v, model.n_coordinates(), "v");
            require_outputs(t, {{&q, "q"}, {&v, "v"}});
            require_inputs(model, inputs, q.rows());
            return velocity_residual(model, view_of(t, &q, &v, nullptr, inputs));
          },
          py::arg("t"), py::arg("q"), py::arg("v"), py::arg("inputs") = RowMajor(),
          "max |Phi_q v + Phi_t| at each state")
      .def(
          "constraint_jacobian",
          [](const Model& model, const Eigen::VectorXd& q, double t) {
            require_rows(model, q.transpose(), model.n_coordinates(), "q");
            Data d(model);
            assemble_jacobian(model, d, q.data(), t);
            return Eigen::MatrixXd(d.Phi_q);
          },
          py::arg("q"), py::arg("t") = 0.0)
      .def(
          "mass_matrix",
          [](const Model& model, const Eigen::VectorXd& q) {
            require_rows(model, q.transpose(), model.n_coordinates(), "q");
            Data d(model);
            assemble_mass(model, d, q.data());
            return py::make_tuple(Eigen::MatrixXd(d.M), Eigen::MatrixXd(d.M_inv));
          },
          py::arg("q"), "M(q) and M(q)^-1 (dense; block diagonal).")
      .def(
          "mass_derivative",
          [](const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& a) {
            require_rows(model, q.transpose(), model.n_coordinates(), "q");
            require_rows(model, a.transpose(), model.n_coordinates(), "a");
            Data d(model);
            assemble_mass_derivative(model, d, q.data(), a.data());
            return Eigen::MatrixXd(d.M_qa);
          },
          py::arg("q"), py::arg("a"), "d(M(q) a)/dq (dense).")
      .def(
          "kinetic_energy",
          [](const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& v) {
            require_rows(model, q.transpose(), model.n_coordinates(), "q");
            require_rows(model, v.transpose(), model.n_coordinates(), "v");
            return kinetic_energy(model, q.data(), v.data());
          },
          py::arg("q"), py::arg("v"))
      .def(
          "constraint_values",
          [](const Model& model, const Eigen::VectorXd& q, double t) {
            require_rows(model, q.transpose(), model.n_coordinates(), "q");
            Data d(model);
            assemble_constraints(model, d, q.data(), t);
            assemble_phi_t(model, d, q.data(), t);
            return py::make_tuple(d.Phi, d.phi_t);
          },
          py::arg("q"), py::arg("t") = 0.0, "(Phi, Phi_t) at (q, t)")
      .def(
          "constraint_hessian",
          [](const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& w, double t) {
            require_rows(model, q.transpose(), model.n_coordinates(), "q");
            require_rows(model, w.transpose(), model.n_constraints(), "w");
            Data d(model);
            assemble_constraint_hessian(model, d, q.data(), t, w.data());
            return Eigen::MatrixXd(d.H);
          },
          py::arg("q"), py::arg("w"), py::arg("t") = 0.0, "sum_r w_r d2Phi_r/dq2")
      .def(
          "gamma",
          [](const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& v, double t) {
            require_rows(model, q.transpose(), model.n_coordinates(), "q");
            require_rows(model, v.transpose(), model.n_coordinates(), "v");
            Data d(model);
            assemble_gamma(model, d, q.data(), v.data(), t);
            assemble_velocity_jacobian(model, d, q.data(), v.data(), t);
            return py::make_tuple(d.gamma, Eigen::MatrixXd(d.Vq));
          },
          py::arg("q"), py::arg("v"), py::arg("t") = 0.0, "(gamma, d(Phi_q v + Phi_t)/dq)")
      .def(
          "forces",
          [](const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& v, double t) {
            require_rows(model, q.transpose(), model.n_coordinates(), "q");
            require_rows(model, v.transpose(), model.n_coordinates(), "v");
            Data d(model);
            assemble_forces(model, d, q.data(), v.data(), t);
            assemble_force_derivatives(model, d, q.data(), v.data(), t);
            return py::make_tuple(d.Q, Eigen::MatrixXd(d.Q_q), Eigen::MatrixXd(d.Q_v));
          },
          py::arg("q"), py::arg("v"), py::arg("t") = 0.0, "(Q, Q_q, Q_v)")
      .def(
          "rank",
          [](const Model& model, const Eigen::VectorXd& q, double t) {
            PythonCall call;
            const ConstraintRank r = constraint_rank(model, q, t);
            py::dict out;
            out["rank"] = r.rank;
            out["equations"] = r.equations;
            out["coordinates"] = r.coordinates;
            out["degrees_of_freedom"] = r.degrees_of_freedom();
            out["dependent_rows"] = r.dependent_rows;
            return out;
          },
          py::arg("q"), py::arg("t") = 0.0);

  py::class_<TimeFunction, TimeFunctionPtr>(m, "TimeFunction",
                                           py::custom_type_setup(collectable<TimeFunction, OwnFunction>))
      .def("__call__", [](const TimeFunction& f, double t) {
        const TimeValue v = f.eval(t);
        return py::make_tuple(v.f, v.df, v.ddf);
      });
  m.def("kinds", &kinds_to_python, "The registry of element kinds (lagmb/registry.hpp) as plain data.");
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
      "The integration methods (lagmb/methods.hpp), one dict each, the default first.");

  m.def(
      "simulate",
      [](const Model& model, const py::dict& options, py::object progress) {
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
          tr = simulate(model, o);
        }
        return to_python(std::move(tr));
      },
      py::arg("model"), py::arg("options"), py::arg("progress") = py::none(),
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
      .def("input", &Simulator::input, py::arg("name"), Release())
      .def_property_readonly("inputs", py::cpp_function(&Simulator::inputs, Release()))
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

  m.def(
      "equilibrium",
      [](const Model& model, double t, double tol, int max_iterations, bool allow_unstable) {
        EquilibriumOptions o;
        o.t = t;
        o.tol = tol;
        o.max_iterations = max_iterations;
        o.allow_unstable = allow_unstable;
        PythonCall call;
        Equilibrium e;
        {
          py::gil_scoped_release release;
          e = find_equilibrium(model, o);
        }
        py::dict out;
        out["q"] = e.q;
        out["lam"] = e.lam;
        out["iterations"] = e.iterations;
        out["stable"] = e.stable;
        out["stiffness_eigenvalues"] = e.stiffness_eigenvalues;
        out["softest_mode"] = e.softest_mode;
        out["force_residual"] = e.force_residual;
        out["constraint_residual"] = e.constraint_residual;
        return out;
      },
      py::arg("model"), py::arg("t") = 0.0, py::arg("tol") = 1e-12, py::arg("max_iterations") = 100,
      py::arg("allow_unstable") = false, "Static equilibrium (see equilibrium.hpp) as a dict.");

  m.def(
      "degrees_of_freedom",
      [](const Model& model, double t) {
        PythonCall call;
        return degrees_of_freedom(model, t);
      },
      py::arg("model"), py::arg("t") = 0.0);
}
