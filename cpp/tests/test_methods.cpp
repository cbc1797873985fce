// The methods table (lagmb/integrators/methods.hpp): every method name maps
// to the formulation and integrator docs/methods.md documents, with what it
// supports; the names of the choices read back to the same choice; names
// and pairs outside the table are refused with the message that lists it.
#include <iterator>
#include <set>
#include <stdexcept>
#include <string>

#include "check.hpp"
#include "lagmb/integrators/methods.hpp"
#include "lagmb/run/simulate.hpp"
#include "models.hpp"

using namespace lagmb_test;

namespace {

/// docs/methods.md, "Formulations and integrators", in the table's order.
struct Documented {
  const char* name;
  Formulation formulation;
  Integrator integrator;
  int max_order;
};
const Documented kDocumented[] = {
    {"ggl", Formulation::kGgl, Integrator::kBdf, 5},
    {"index3", Formulation::kIndex3, Integrator::kBdf, 5},
    {"index1", Formulation::kIndex1, Integrator::kBdf, 5},
    {"projection-bdf", Formulation::kProjection, Integrator::kBdf, 5},
    {"projection-adams", Formulation::kProjection, Integrator::kAdams, 12},
    {"projection-erk", Formulation::kProjection, Integrator::kErk, 8},
    {"ali3p", Formulation::kAli3p, Integrator::kTrapezoidal, 2},
};

const Method& named(const std::string& name) {
  for (const Method& m : methods())
    if (m.name == name) return m;
  throw std::logic_error("no method " + name);
}

/// The names of the methods with a capability, in the table's order.
std::string having(bool Method::*capability) {
  std::string s;
  for (const Method& m : methods())
    if (m.*capability) s += (s.empty() ? "" : " ") + m.name;
  return s;
}

SimulationOptions quick(Formulation f, Integrator i = Integrator::kDefault) {
  SimulationOptions o;
  o.t_end = 0.01;
  o.formulation = f;
  o.integrator = i;
  return o;
}

}  // namespace

TEST_CASE(every_method_is_the_formulation_and_integrator_documented) {
  CHECK(methods().size() == std::size(kDocumented));
  CHECK(methods().front().name == "ggl");  // first: what "auto" runs for stiff forces, contact and friction
  std::set<std::string> names;
  for (const Method& m : methods()) names.insert(m.name);
  CHECK(names.size() == methods().size());
  for (const Documented& doc : kDocumented) {
    const Method& m = named(doc.name);
    CHECK(m.formulation == doc.formulation && m.integrator == doc.integrator);
    CHECK(m.max_order == doc.max_order);
    CHECK(&find_method(doc.formulation, doc.integrator) == &m);
    // a name of a choice reads back to it
    CHECK(choice_from<Formulation>(name_of(m.formulation)) == m.formulation);
    CHECK(choice_from<Integrator>(name_of(m.integrator)) == m.integrator);
    // the name is the formulation's, with the integrator where it has several
    const std::string formulation = name_of(doc.formulation);
    CHECK(m.name == formulation || m.name == formulation + "-" + name_of(doc.integrator));
    CHECK(!m.description.empty() && !m.solver.empty());
  }
}

TEST_CASE(the_integrator_defaults_to_the_formulations_first) {
  CHECK(find_method(Formulation::kGgl, Integrator::kDefault).name == "ggl");
  CHECK(find_method(Formulation::kIndex3, Integrator::kDefault).name == "index3");
  CHECK(find_method(Formulation::kIndex1, Integrator::kDefault).name == "index1");
  CHECK(find_method(Formulation::kProjection, Integrator::kDefault).name == "projection-bdf");
  CHECK(find_method(Formulation::kAli3p, Integrator::kDefault).name == "ali3p");
}

TEST_CASE(what_each_method_supports_is_as_documented) {
  CHECK(having(&Method::fixed_step) == "ali3p");
  CHECK(having(&Method::baumgarte) == "index1 projection-adams");
  CHECK(having(&Method::drifts) == "index1 projection-adams");
  CHECK(having(&Method::events) == "ggl index3 index1 projection-bdf projection-adams projection-erk ali3p");
  CHECK(having(&Method::contact) == "ggl index3 index1 projection-bdf projection-adams");
  CHECK(having(&Method::friction) == "ggl index3 index1 projection-bdf projection-adams projection-erk");
}

TEST_CASE(names_outside_the_table_are_refused_listing_it) {
  CHECK_THROWS(ModelError, choice_from<Formulation>("rk4"),
               "unknown formulation 'rk4' (the choices are auto, ggl, index3, index1, projection, ali3p)");
  CHECK_THROWS(ModelError, choice_from<Integrator>("rk4"),
               "unknown integrator 'rk4' (the choices are bdf, adams, erk, trapezoidal)");
  // a method's name is no formulation in C++ (Python reads it: method_options)
  CHECK_THROWS(ModelError, choice_from<Formulation>("projection-erk"), "unknown formulation 'projection-erk'");
  CHECK_THROWS(ModelError, find_method(Formulation::kGgl, Integrator::kAdams),
               "integrator 'adams': formulation 'ggl' is integrated by 'bdf', not by 'adams' (the methods are: "
               "ggl with bdf, index3 with bdf, index1 with bdf, projection with bdf, projection with adams, "
               "projection with erk, ali3p with trapezoidal)");
  CHECK_THROWS(ModelError, find_method(Formulation::kProjection, Integrator::kTrapezoidal),
               "formulation 'projection' is integrated by 'bdf', 'adams', 'erk', not by 'trapezoidal'");
}

TEST_CASE(a_run_is_refused_what_its_method_does_not_do) {
  const auto model = pendulum();
  CHECK_THROWS(ModelError, simulate(*model, quick(Formulation::kAuto, Integrator::kAdams)),
               "integrator 'adams' needs its formulation: formulation 'auto' chooses both");
  CHECK_THROWS(ModelError, simulate(*model, quick(Formulation::kAli3p)),
               "formulation 'ali3p' takes fixed steps: give the step as max_step");
  SimulationOptions o = quick(Formulation::kProjection);
  o.max_order = 6;
  CHECK_THROWS(ModelError, simulate(*model, o), "max_order must be in 1..5 for projection-bdf");
  o = quick(Formulation::kGgl);
  o.baumgarte_alpha = 1.0;
  CHECK_THROWS(ModelError, simulate(*model, o), "Baumgarte terms apply to the methods index1, projection-adams");
}

TEST_CASE(a_fixed_step_method_refuses_the_tolerances_of_error_control) {
  // ali3p has no error control: rtol and atol given to it would be ignored
  // silently; its Newton iteration has tolerances of its own
  const auto model = pendulum();
  const char* refused =
      "simulate: formulation 'ali3p' takes fixed steps without error control: rtol and atol do not apply; its "
      "Newton corrections are bounded by newton_rtol (default 1e-10) and newton_atol (default 1e-12)";
  SimulationOptions o = quick(Formulation::kAli3p);
  o.max_step = 1e-3;
  o.rtol = 1e-10;
  CHECK_THROWS(ModelError, simulate(*model, o), refused);
  o = quick(Formulation::kAli3p);
  o.max_step = 1e-3;
  o.atol = 1e-12;
  CHECK_THROWS(ModelError, simulate(*model, o), refused);
  o = quick(Formulation::kAli3p);
  o.max_step = 1e-3;
  o.atol_coordinates.assign(model->n_coordinates(), 1e-8);
  CHECK_THROWS(ModelError, simulate(*model, o), refused);
  o = quick(Formulation::kAli3p);
  o.max_step = 1e-3;
  o.newton_rtol = 1e-8;  // its own tolerances it takes
  CHECK(simulate(*model, o).t.size() > 1);
}

LAGMB_TEST_MAIN()
