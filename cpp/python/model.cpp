// lagmb._core: the model description (ModelSpec: building a model), the compiled
// Model (its queries: model_queries.cpp) and the registry of kinds.
#include "common.hpp"

namespace lagmb::python {

namespace {

/// A point as Python has it: (x, y) in a planar model, (x, y, z) in a spatial one.
py::tuple point_of(const Model& model, const Vec3& p) {
  if (model.dimension() == 2) return py::make_tuple(p.x(), p.y());
  return py::make_tuple(p.x(), p.y(), p.z());
}

}  // namespace

py::list outline_of(const Model& model, int body) {
  py::list out;
  for (const Vec3& p : model.outline(body)) out.append(point_of(model, p));
  return out;
}

py::list attachments_of(const Model& model, const std::string& element) {
  py::list out;
  for (const auto& [body, p] : model.attachments(element))
    out.append(py::tuple(py::make_tuple(body) + point_of(model, p)));
  return out;
}

namespace {

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
    case ParamType::kShape: {  // (body index, kind, size (3), position (3), axes (3 x 3), vertices [(3)])
      const auto t = x.cast<py::tuple>();
      CollisionShape shape;
      shape.body = t[0].cast<int>();
      shape.kind = shape_kind(t[1].cast<std::string>());
      shape.size = t[2].cast<Vec3>();
      shape.position = t[3].cast<Vec3>();
      shape.axes = t[4].cast<Mat3>();
      for (py::handle v : t[5]) shape.vertices.push_back(v.cast<Vec3>());
      return shape;
    }
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

/// A value as the spec holds it, as Python has it: numbers, tuples (nested
/// for a matrix), flags, text, a body's index, time functions as core objects.
py::object value_to_python(const Value& v) {
  if (const auto* b = std::get_if<BodyIndex>(&v)) return py::int_(b->index);
  if (const auto* m = std::get_if<Mat3>(&v))
    return py::make_tuple(py::make_tuple((*m)(0, 0), (*m)(0, 1), (*m)(0, 2)),
                          py::make_tuple((*m)(1, 0), (*m)(1, 1), (*m)(1, 2)),
                          py::make_tuple((*m)(2, 0), (*m)(2, 1), (*m)(2, 2)));
  if (const auto* f = std::get_if<TimeFunctionPtr>(&v)) return py::cast(*f);
  if (const auto* fs = std::get_if<std::pair<TimeFunctionPtr, TimeFunctionPtr>>(&v))
    return py::make_tuple(py::cast(fs->first), py::cast(fs->second));
  if (const auto* c = std::get_if<CollisionShape>(&v)) {
    py::list vertices;
    for (const Vec3& x : c->vertices) vertices.append(py::make_tuple(x.x(), x.y(), x.z()));
    return py::make_tuple(c->body, shape_kind_name(c->kind), py::make_tuple(c->size.x(), c->size.y(), c->size.z()),
                          py::make_tuple(c->position.x(), c->position.y(), c->position.z()),
                          value_to_python(Value(c->axes)), vertices);
  }
  if (const auto* f3 = std::get_if<std::array<TimeFunctionPtr, 3>>(&v))
    return py::make_tuple(py::cast((*f3)[0]), py::cast((*f3)[1]), py::cast((*f3)[2]));
  return default_to_python(v);
}

/// The registry as plain Python data (lagmb.registry reads it).
py::list kinds_to_python() {
  py::list out;
  for (const KindInfo& k : element_kinds()) {
    py::list params;
    for (const Param& p : k.params) {
      py::dict d;
      d["name"] = p.name;
      d["type"] = param_type(p.type).name;
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
    d["coordinate"] = coordinate_name(k.coordinate);
    d["effort"] = k.effort;
    d["effort_components"] = py::tuple(py::cast(k.effort_components));
    out.append(d);
  }
  return out;
}

/// Building a model: the description users add elements to, and its compilation.
void bind_model_spec(py::module_& m) {
  py::class_<ModelSpec>(m, "ModelSpec", py::custom_type_setup(collectable<ModelSpec, SpecFunctions>))
      .def(py::init<int>(), py::arg("dimension") = 2)
      .def("__copy__", [](const ModelSpec& spec) { return spec.copied(own); })
      .def("__len__", [](const ModelSpec& spec) { return spec.elements().size(); })
      .def_property_readonly("dimension", &ModelSpec::dimension)
      .def_property_readonly("element_builds", &ModelSpec::element_builds,
                             "Elements built into models by this spec so far (by add and by rebuilding).")
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
          "elements",
          [](const ModelSpec& spec) {
            py::list out;
            for (const ModelSpec::Element& e : spec.elements()) {
              py::dict values;
              for (const auto& [key, value] : e.args.values()) values[py::str(key)] = value_to_python(value);
              out.append(py::make_tuple(e.args.kind().name, e.name, values));
            }
            return out;
          },
          "(kind, name, {parameter: value}) of every element as given, in the order added: the one "
          "description lagmb.Model reads (bodies as indices, time functions as core functions).")
      .def(
          "body_index",
          [](const ModelSpec& spec, const std::string& name) {
            const Model& draft = spec.draft();
            if (!draft.has(name) || draft.find(name).type != ElementRef::kBody) return -2;
            return draft.find(name).group;
          },
          py::arg("name"), "The index of the body called `name`, -2 if there is none.")
      .def_property_readonly("bodies",
                             [](const ModelSpec& spec) {
                               py::list out;
                               const Model& draft = spec.draft();
                               for (const Body& b : draft.bodies()) out.append(py::make_tuple(b.name, b.particle));
                               return out;
                             })
      .def(
          "outline",
          [](const ModelSpec& spec, int body) { return outline_of(spec.draft(), body); },
          py::arg("body"))
      .def(
          "attachments",
          [](const ModelSpec& spec, const std::string& element) { return attachments_of(spec.draft(), element); },
          py::arg("element"));
}

/// The registry of element kinds and the types of their parameters, as plain data.
void bind_registry(py::module_& m) {
  m.def(
      "param_types",
      [] {
        py::list out;
        for (const ParamTypeInfo& t : param_types()) {
          py::dict d;
          d["name"] = t.name;
          d["takes"] = t.takes;
          out.append(d);
        }
        return out;
      },
      "The types of element parameters (lagmb/model/registry.hpp, param_types()), in order.");
  m.def("reaction_components", &reaction_components, py::arg("dimension"),
        "The names of a reaction's components (Model.reaction's columns): x, y, torque; in space x, y, z, "
        "torque.x, torque.y, torque.z.");
  m.def("kinds", &kinds_to_python, "The registry of element kinds (lagmb/model/registry.hpp) as plain data.");
}

}  // namespace

void bind_model(py::module_& m) {
  bind_model_spec(m);
  // compiled models come from ModelSpec.compile(); nothing here changes one
  ModelClass model(m, "Model", py::custom_type_setup(collectable<Model, ModelFunctions>));
  bind_model_structure(model);
  bind_model_readings(model);
  bind_model_terms(model);
  bind_registry(m);
}

}  // namespace lagmb::python
