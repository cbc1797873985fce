// lagmb._core: the model description (ModelSpec), the compiled Model and the registry of kinds.
#include "common.hpp"

namespace lagmb::python {

namespace {

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

}  // namespace

void bind_model(py::module_& m) {
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

  // compiled models come from ModelSpec.compile(); nothing here changes one
  py::class_<Model, std::shared_ptr<Model>>(m, "Model", py::custom_type_setup(collectable<Model, ModelFunctions>))
      .def("outline", &outline_of, py::arg("body"))
      .def("attachments", &attachments_of, py::arg("element"))
      .def_property_readonly("finalized", &Model::finalized)
      .def_property_readonly("n_coordinates", &Model::n_coordinates)
      .def_property_readonly("n_constraints", &Model::n_constraints)
      .def_property_readonly("unilateral_rows", &Model::unilateral_rows,
                             "The rows of Phi that are stops' gaps (open unless a run holds the joint on a limit)")
      .def_property_readonly("dimension", &Model::dimension)
      .def_property_readonly("run_state_size", &Model::run_state_size,
                             "Doubles of per-run element state (a Result's run_state columns): the turns of the "
                             "spatial joints, a contact's impact speed")
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
      .def("joint_coordinate",
           [](const Model& model, const std::string& name) -> py::object {
             const ElementRef& r = model.find(name);
             if (r.type != ElementRef::kConstraint) return py::none();
             const std::optional<JointCoordinate> c = model.constraint_groups()[r.group]->coordinate(r.index);
             if (!c) return py::none();
             py::dict d;
             d["turns"] = c->turns;
             d["slides"] = c->slides;
             d["bodies"] = py::make_tuple(c->body_i, c->body_j);
             return d;
           },
           py::arg("name"), "What the joint's scalar coordinate is (its kind's coordinate()), or None.")
      .def("element_kind",
           [](const Model& model, const std::string& name) -> std::string {
             const ElementRef& r = model.find(name);
             if (r.type == ElementRef::kBody) return "body";
             if (r.type == ElementRef::kConstraint) return model.constraint_groups()[r.group]->kind();
             if (r.type == ElementRef::kFriction) return model.friction_groups()[r.group]->kind();
             if (r.type == ElementRef::kEvent) return model.event_groups()[r.group]->kind();
             return model.force_groups()[r.group]->kind();
           })
      .def(
          "given_kind",
          [](const Model& model, const std::string& name) -> py::object {
            const KindInfo* kind = model.given_kind(name);
            return kind ? py::object(py::str(kind->name)) : py::object(py::none());
          },
          py::arg("name"), "The registry kind the body or element was added as (lagmb.registry.BY_NAME), or None.")
      .def("coordinate_names", &coordinate_names,
           "The names of the coordinates q in order: body.x, body.y, body.angle, ... (coordinates.hpp).")
      .def("coordinate_units", &coordinate_units, "Their units: rad, m, or '' (an Euler parameter).")
      .def("initial_state",
           [](const Model& model) { return py::make_tuple(model.initial_q(), model.initial_v()); })
      .def(
          "reaction",
          [](const Model& model, const std::string& name, const Eigen::VectorXd& t, const RowMajor& q,
             const RowMajor& lam, bool joint_axes, const RowMajor& inputs, const RowMajor& state, bool about_joint) {
            require_rows(model, q, model.n_coordinates(), "q");
            require_rows(model, lam, model.n_constraints(), "lam");
            require_outputs(t, {{&q, "q"}, {&lam, "lam"}});
            require_inputs(model, inputs, q.rows());
            require_state(model, state, q.rows());
            return reactions(model, name, view_of(t, &q, nullptr, &lam, inputs, state), joint_axes, about_joint);
          },
          py::arg("name"), py::arg("t"), py::arg("q"), py::arg("lam"), py::arg("joint_axes") = false,
          py::arg("inputs") = RowMajor(), py::arg("state") = RowMajor(), py::arg("about_joint") = false,
          "Force and torque about the centre of mass that the element applies to its second body\n"
          "((x, y) and the torque in the plane, (x, y, z) and (x, y, z) in space); with joint_axes,\n"
          "in the element's own axes; with about_joint, the torque about the joint's point on that body.")
      .def(
          "effort",
          [](const Model& model, const std::string& name, const Eigen::VectorXd& t, const RowMajor& q,
             const RowMajor& v, const RowMajor& lam, const RowMajor& inputs, const RowMajor& state) {
            require_rows(model, q, model.n_coordinates(), "q");
            require_rows(model, v, model.n_coordinates(), "v");
            require_outputs(t, {{&q, "q"}, {&v, "v"}});
            if (lam.size()) {
              require_rows(model, lam, model.n_constraints(), "lam");
              require_outputs(t, {{&lam, "lam"}});
            }
            require_inputs(model, inputs, q.rows());
            require_state(model, state, q.rows());
            return efforts(model, name, view_of(t, &q, &v, lam.size() ? &lam : nullptr, inputs, state));
          },
          py::arg("name"), py::arg("t"), py::arg("q"), py::arg("v"), py::arg("lam") = RowMajor(),
          py::arg("inputs") = RowMajor(), py::arg("state") = RowMajor(),
          "What the element applies at each state, (k, width) as its kind's registry entry says\n"
          "(Kind.effort, effort_components); a driver, stop or joint friction needs lam")
      .def(
          "joint_motion",
          [](const Model& model, const std::string& joint, bool slide, const RowMajor& q, const RowMajor& v,
             const RowMajor& a, const RowMajor& state) {
            require_rows(model, q, model.n_coordinates(), "q");
            require_rows(model, v, model.n_coordinates(), "v");
            if (a.size()) require_rows(model, a, model.n_coordinates(), "a");
            if (v.rows() != q.rows() || (a.size() && a.rows() != q.rows()))
              throw ModelError("q, v and a must have one row per state");
            require_state(model, state, q.rows());
            RowMajor out(q.rows(), 3);
            for (Eigen::Index k = 0; k < q.rows(); ++k) {
              const JointMotion m = joint_motion(model, joint, slide, q.row(k).data(), v.row(k).data(),
                                                 a.size() ? a.row(k).data() : nullptr,
                                                 state.size() ? state.row(k).data() : nullptr);
              out.row(k) << m.value, m.rate, m.acceleration;
            }
            return out;
          },
          py::arg("joint"), py::arg("slide"), py::arg("q"), py::arg("v"), py::arg("a") = RowMajor(),
          py::arg("state") = RowMajor(),
          "(value, rate, acceleration) of a joint's angle (or, with slide, its slide) at each state (rows of q, "
          "v, a); a spatial angle within half a turn of the one the run's state holds (rows of `state`: a "
          "Result's run_state), or without it of the joint's initial angle")
      .def(
          "joint_motions",
          [](const Model& model, const std::vector<std::pair<std::string, bool>>& joints, const Eigen::VectorXd& q,
             const Eigen::VectorXd& v, const Eigen::VectorXd& state) {
            if (q.size() != model.n_coordinates() || v.size() != model.n_coordinates())
              throw ModelError("joint_motions: q and v must have " + std::to_string(model.n_coordinates()) + " entries");
            if (state.size() != model.run_state_size())
              throw ModelError("joint_motions: state must have " + std::to_string(model.run_state_size()) + " entries");
            RowMajor out(joints.size(), 2);
            for (size_t k = 0; k < joints.size(); ++k) {
              const JointMotion m = joint_motion(model, joints[k].first, joints[k].second, q.data(), v.data(), nullptr,
                                                 state.size() ? state.data() : nullptr);
              out.row(Eigen::Index(k)) << m.value, m.rate;
            }
            return out;
          },
          py::arg("joints"), py::arg("q"), py::arg("v"), py::arg("state"),
          "(value, rate) of several joints' angles (or slides: (name, slide) pairs) at one state, as joint_motion "
          "reads each")
      .def(
          "inverse_dynamics",
          [](const Model& model, const std::vector<std::pair<std::string, bool>>& joints, const Eigen::VectorXd& t,
             const RowMajor& q, const RowMajor& v, const RowMajor& a) {
            require_rows(model, q, model.n_coordinates(), "q");
            require_rows(model, v, model.n_coordinates(), "v");
            require_rows(model, a, model.n_coordinates(), "a");
            require_outputs(t, {{&q, "q"}, {&v, "v"}, {&a, "a"}});
            std::vector<JointEffort> efforts;
            for (const auto& [joint, slide] : joints) efforts.push_back({joint, slide});
            RowMajor out(q.rows(), Eigen::Index(efforts.size()));
            for (Eigen::Index k = 0; k < q.rows(); ++k)
              out.row(k) = inverse_dynamics(model, efforts, q.row(k).data(), v.row(k).data(), a.row(k).data(), t[k])
                               .efforts.transpose();
            return out;
          },
          py::arg("joints"), py::arg("t"), py::arg("q"), py::arg("v"), py::arg("a"),
          "The efforts of the joints [(name, slide)] that make each state (t, q, v, a): (k, joints)")
      .def(
          "contact",
          [](const Model& model, const std::string& name, const Eigen::VectorXd& t, const RowMajor& q,
             const RowMajor& v, const RowMajor& state, const RowMajor& lam) {
            require_rows(model, q, model.n_coordinates(), "q");
            require_rows(model, v, model.n_coordinates(), "v");
            require_outputs(t, {{&q, "q"}, {&v, "v"}});
            require_state(model, state, q.rows());
            if (lam.size()) {
              require_rows(model, lam, model.n_constraints(), "lam");
              require_outputs(t, {{&lam, "lam"}});
            }
            return contacts(model, name, view_of(t, &q, &v, lam.size() ? &lam : nullptr, RowMajor(), state));
          },
          py::arg("name"), py::arg("t"), py::arg("q"), py::arg("v"), py::arg("state") = RowMajor(),
          py::arg("lam") = RowMajor(),
          "The contact at each state: (normal force, friction force (dimension), point (dimension),\n"
          "normal (dimension), penetration, slip speed, state (0 open, 1 slip, 2 stick)); a contact\n"
          "that sticks needs the multipliers lam (the friction its rows hold)")
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
             const RowMajor& inputs, const RowMajor& state) {
            require_rows(model, q, model.n_coordinates(), "q");
            require_rows(model, v, model.n_coordinates(), "v");
            require_outputs(t, {{&q, "q"}, {&v, "v"}});
            require_inputs(model, inputs, q.rows());
            require_state(model, state, q.rows());
            return energy(model, view_of(t, &q, &v, nullptr, inputs, state));
          },
          py::arg("t"), py::arg("q"), py::arg("v"), py::arg("inputs") = RowMajor(), py::arg("state") = RowMajor())
      .def(
          "residual",
          [](const Model& model, const Eigen::VectorXd& t, const RowMajor& q, const RowMajor& inputs,
             const RowMajor& state) {
            require_rows(model, q, model.n_coordinates(), "q");
            require_outputs(t, {{&q, "q"}});
            require_inputs(model, inputs, q.rows());
            require_state(model, state, q.rows());
            return constraint_residual(model, view_of(t, &q, nullptr, nullptr, inputs, state));
          },
          py::arg("t"), py::arg("q"), py::arg("inputs") = RowMajor(), py::arg("state") = RowMajor(),
          "max |Phi| at each state")
      .def(
          "velocity_residual",
          [](const Model& model, const Eigen::VectorXd& t, const RowMajor& q, const RowMajor& v,
             const RowMajor& inputs, const RowMajor& state) {
            require_rows(model, q, model.n_coordinates(), "q");
            require_rows(model, v, model.n_coordinates(), "v");
            require_outputs(t, {{&q, "q"}, {&v, "v"}});
            require_inputs(model, inputs, q.rows());
            require_state(model, state, q.rows());
            return velocity_residual(model, view_of(t, &q, &v, nullptr, inputs, state));
          },
          py::arg("t"), py::arg("q"), py::arg("v"), py::arg("inputs") = RowMajor(), py::arg("state") = RowMajor(),
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

}  // namespace lagmb::python
