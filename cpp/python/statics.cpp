// lagmb._core: static equilibrium and degrees of freedom.
#include "common.hpp"

namespace lagmb::python {

namespace {

/// A sparse matrix as (rows, cols, values, shape), which Python turns into
/// a dense array or a SciPy matrix (SciPy is not a dependency of lagmb).
py::tuple triplets(const SpMat& A) {
  std::vector<int> rows, cols;
  std::vector<double> values;
  rows.reserve(A.nonZeros()), cols.reserve(A.nonZeros()), values.reserve(A.nonZeros());
  for (int j = 0; j < A.outerSize(); ++j)
    for (SpMat::InnerIterator it(A, j); it; ++it) {
      rows.push_back(int(it.row()));
      cols.push_back(int(it.col()));
      values.push_back(it.value());
    }
  return py::make_tuple(rows, cols, values, py::make_tuple(A.rows(), A.cols()));
}

}  // namespace

void bind_statics(py::module_& m) {
  m.def(
      "equilibrium",
      [](const Model& model, double t, double tol, int max_iterations, bool allow_unstable, bool stability) {
        EquilibriumOptions o;
        o.t = t;
        o.tol = tol;
        o.max_iterations = max_iterations;
        o.allow_unstable = allow_unstable;
        o.stability = stability;
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
        out["stable"] = e.stability_checked ? py::object(py::bool_(e.stable)) : py::object(py::none());
        out["dropped_rows"] = e.dropped_rows;
        out["stiffness_eigenvalues"] = e.stiffness_eigenvalues;
        out["softest_mode"] = e.softest_mode;
        out["force_residual"] = e.force_residual;
        out["constraint_residual"] = e.constraint_residual;
        return out;
      },
      py::arg("model"), py::arg("t") = 0.0, py::arg("tol") = 1e-12, py::arg("max_iterations") = 100,
      py::arg("allow_unstable") = false, py::arg("stability") = true, "Static equilibrium (see equilibrium.hpp) as a dict.");

  m.def(
      "tangent_at_rest",
      [](const Model& model, const VecX& q, const VecX& lam, double t, const std::vector<int>& dropped_rows) {
        PythonCall call;
        RestTangent r = tangent_at_rest(model, q, lam, t, dropped_rows);
        py::dict out;
        out["M"] = r.M;
        out["K"] = r.K;
        out["C"] = r.C;
        out["Phi_q"] = r.Phi_q;
        return out;
      },
      py::arg("model"), py::arg("q"), py::arg("lam"), py::arg("t"), py::arg("dropped_rows"),
      "M, K = (Phi_q^T lam)_q - Q_q, C = -Q_v and Phi_q at rest (linearization.hpp), dense.");

  m.def(
      "tangent_at",
      [](const Model& model, const VecX& q, const VecX& v, double t, const VecX& u,
         const std::optional<std::vector<int>>& dropped_rows, const std::vector<std::string>& held) {
        PythonCall call;
        StateTangent r;
        {
          py::gil_scoped_release release;
          r = tangent_at(model, q, v, t, u, dropped_rows, held);
        }
        py::dict out;
        out["dropped_rows"] = r.dropped_rows;
        out["a"] = r.a;
        out["lam"] = r.lam;
        out["Q"] = r.Q;
        out["gamma"] = r.gamma;
        out["Phi"] = r.Phi;
        out["velocity_residual"] = r.velocity_residual;
        out["M"] = triplets(r.M);
        out["Phi_q"] = triplets(r.Phi_q);
        out["K"] = triplets(r.K);
        out["C"] = triplets(r.C);
        out["G_q"] = triplets(r.G_q);
        out["G_v"] = triplets(r.G_v);
        out["Q_u"] = r.Q_u;
        out["Phi_u"] = r.Phi_u;
        return out;
      },
      py::arg("model"), py::arg("q"), py::arg("v"), py::arg("t"), py::arg("inputs"), py::arg("dropped_rows") = py::none(),
      py::arg("held") = std::vector<std::string>(),
      "The linearization's terms at a state (linearization.hpp, StateTangent): a, lam, Q, gamma, Phi, "
      "velocity_residual, Q_u, Phi_u dense; M, Phi_q, K, C, G_q, G_v as (rows, cols, values, shape).");

  m.def(
      "degrees_of_freedom",
      [](const Model& model, double t) {
        PythonCall call;
        return degrees_of_freedom(model, t);
      },
      py::arg("model"), py::arg("t") = 0.0);
}

}  // namespace lagmb::python
