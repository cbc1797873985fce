// lagmb._core: what a compiled Model answers: what it is (its structure), what
// it reads at a run's outputs (readings), and the terms of its equations at one
// state (terms). Every array a query reads is checked by Given (common.hpp).
#include "common.hpp"

namespace lagmb::python {

/// Sizes, names, inputs, parameters, and what each element is.
void bind_model_structure(ModelClass& model) {
  model
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
           [](const Model& model) { return py::make_tuple(model.initial_q(), model.initial_v()); });
}

/// What the model reads at the states of a run's outputs (rows of q, v,
/// lam, ... at the times t): reactions, efforts, joint motions, contacts,
/// friction, energy and the residuals.
void bind_model_readings(ModelClass& model) {
  model
      .def(
          "reaction",
          [](const Model& model, const std::string& name, const Eigen::VectorXd& t, const RowMajor& q,
             const RowMajor& lam, bool joint_axes, const RowMajor& inputs, const RowMajor& state, bool about_joint) {
            Given(model, t).coordinates(q, "q").multipliers(lam, "lam").inputs(inputs).state(state);
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
            Given(model, t).coordinates(q, "q").coordinates(v, "v").multipliers_if_given(lam).inputs(inputs).state(
                state);
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
            const Given given(model, q.rows());
            given.coordinates(q, "q").coordinates(v, "v");
            if (a.size()) given.coordinates(a, "a");
            if (v.rows() != q.rows() || (a.size() && a.rows() != q.rows()))
              throw ModelError("q, v and a must have one row per state");
            given.state(state);
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
            Given(model, t).coordinates(q, "q").coordinates(v, "v").coordinates(a, "a");
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
            Given(model, t).coordinates(q, "q").coordinates(v, "v").state(state).multipliers_if_given(lam);
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
            Given(model).coordinates(q, "q").coordinates(v, "v").multipliers(lam, "lam");
            if (v.rows() != q.rows() || lam.rows() != q.rows())
              throw ModelError("q, v and lam must have one row per output (got " + std::to_string(q.rows()) + ", " +
                               std::to_string(v.rows()) + " and " + std::to_string(lam.rows()) + ")");
            const Eigen::VectorXd t = Eigen::VectorXd::Zero(q.rows());  // (friction does not depend on t)
            return friction(model, name, view_of(t, &q, &v, &lam, RowMajor()));
          },
          py::arg("name"), py::arg("q"), py::arg("v"), py::arg("lam"),
          "(friction torque or force on the joint's second body, slip rate) at each state")
      .def(
          "energy",
          [](const Model& model, const Eigen::VectorXd& t, const RowMajor& q, const RowMajor& v,
             const RowMajor& inputs, const RowMajor& state) {
            Given(model, t).coordinates(q, "q").coordinates(v, "v").inputs(inputs).state(state);
            return energy(model, view_of(t, &q, &v, nullptr, inputs, state));
          },
          py::arg("t"), py::arg("q"), py::arg("v"), py::arg("inputs") = RowMajor(), py::arg("state") = RowMajor())
      .def(
          "residual",
          [](const Model& model, const Eigen::VectorXd& t, const RowMajor& q, const RowMajor& inputs,
             const RowMajor& state) {
            Given(model, t).coordinates(q, "q").inputs(inputs).state(state);
            return constraint_residual(model, view_of(t, &q, nullptr, nullptr, inputs, state));
          },
          py::arg("t"), py::arg("q"), py::arg("inputs") = RowMajor(), py::arg("state") = RowMajor(),
          "max |Phi| at each state")
      .def(
          "velocity_residual",
          [](const Model& model, const Eigen::VectorXd& t, const RowMajor& q, const RowMajor& v,
             const RowMajor& inputs, const RowMajor& state) {
            Given(model, t).coordinates(q, "q").coordinates(v, "v").inputs(inputs).state(state);
            return velocity_residual(model, view_of(t, &q, &v, nullptr, inputs, state));
          },
          py::arg("t"), py::arg("q"), py::arg("v"), py::arg("inputs") = RowMajor(), py::arg("state") = RowMajor(),
          "max |Phi_q v + Phi_t| at each state");
}

/// The terms of the equations of motion at one state: Phi and its
/// derivatives, M(q), gamma, Q and its derivatives, joint friction, the rank.
void bind_model_terms(ModelClass& model) {
  model
      .def(
          "constraint_jacobian",
          [](const Model& model, const Eigen::VectorXd& q, double t) {
            Given(model).coordinates(q, "q");
            Data d(model);
            assemble_jacobian(model, d, q.data(), t);
            return Eigen::MatrixXd(d.Phi_q);
          },
          py::arg("q"), py::arg("t") = 0.0)
      .def(
          "mass_matrix",
          [](const Model& model, const Eigen::VectorXd& q) {
            Given(model).coordinates(q, "q");
            Data d(model);
            assemble_mass(model, d, q.data());
            assemble_mass_inverse(model, d, q.data());
            return py::make_tuple(Eigen::MatrixXd(d.M), Eigen::MatrixXd(d.M_inv));
          },
          py::arg("q"), "M(q) and M(q)^-1 (dense; block diagonal).")
      .def(
          "mass_derivative",
          [](const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& a) {
            Given(model).coordinates(q, "q").coordinates(a, "a");
            Data d(model);
            assemble_mass_derivative(model, d, q.data(), a.data());
            return Eigen::MatrixXd(d.M_qa);
          },
          py::arg("q"), py::arg("a"), "d(M(q) a)/dq (dense).")
      .def(
          "kinetic_energy",
          [](const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& v) {
            Given(model).coordinates(q, "q").coordinates(v, "v");
            return kinetic_energy(model, q.data(), v.data());
          },
          py::arg("q"), py::arg("v"))
      .def(
          "constraint_values",
          [](const Model& model, const Eigen::VectorXd& q, double t) {
            Given(model).coordinates(q, "q");
            Data d(model);
            assemble_constraints(model, d, q.data(), t);
            assemble_phi_t(model, d, q.data(), t);
            return py::make_tuple(d.Phi, d.phi_t);
          },
          py::arg("q"), py::arg("t") = 0.0, "(Phi, Phi_t) at (q, t)")
      .def(
          "constraint_hessian",
          [](const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& w, double t) {
            Given(model).coordinates(q, "q").multipliers(w, "w");
            Data d(model);
            assemble_constraint_hessian(model, d, q.data(), t, w.data());
            return Eigen::MatrixXd(d.H);
          },
          py::arg("q"), py::arg("w"), py::arg("t") = 0.0, "sum_r w_r d2Phi_r/dq2")
      .def(
          "gamma",
          [](const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& v, double t) {
            Given(model).coordinates(q, "q").coordinates(v, "v");
            Data d(model);
            assemble_gamma(model, d, q.data(), v.data(), t);
            assemble_velocity_jacobian(model, d, q.data(), v.data(), t);
            return py::make_tuple(d.gamma, Eigen::MatrixXd(d.Vq));
          },
          py::arg("q"), py::arg("v"), py::arg("t") = 0.0, "(gamma, d(Phi_q v + Phi_t)/dq)")
      .def(
          "forces",
          [](const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& v, double t) {
            Given(model).coordinates(q, "q").coordinates(v, "v");
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
          py::arg("q"), py::arg("t") = 0.0)
      .def(
          "friction_forces",
          [](const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& v, const Eigen::VectorXd& lam) {
            Given(model).coordinates(q, "q").coordinates(v, "v").multipliers(lam, "lam");
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
          py::arg("q"), py::arg("v"), py::arg("lam"), "(Q_f, dQ_f/dq, dQ_f/dv, dQ_f/dlam) of joint friction");
}

}  // namespace lagmb::python
