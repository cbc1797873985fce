// Run-time parameters (parameters.hpp): the table, and a model built again with other values.
#include "lagmb/spec/parameters.hpp"

#include <cmath>

#include "lagmb/model/coordinates.hpp"

namespace lagmb {

namespace {

const char* component_name(int c) { return c == 0 ? "x" : c == 1 ? "y" : "z"; }

}  // namespace

std::vector<ParameterInfo> parameters(const Model& model) {
  std::vector<ParameterInfo> out;
  for (const GivenElement& e : model.given_elements()) {
    const KindInfo& kind = e.args.kind();
    for (const Param& p : kind.params) {
      const Value& v = e.args.get(p.name);
      auto add = [&](int component, double x) {
        ParameterInfo info{e.name + "." + p.name, e.name, p.name, component, p.unit, p.doc, x};
        std::string suffix = p.name;
        if (component >= 0) {
          suffix += std::string(".") + component_name(component);
          info.name += std::string(".") + component_name(component);
        }
        // a body's coordinate of that name (an FMU output) would be shadowed
        if (kind.role == Role::kBody && is_body_coordinate_name(suffix)) info.name += ".start";
        out.push_back(std::move(info));
      };
      if (p.type == ParamType::kReal) {
        if (const double* x = std::get_if<double>(&v)) add(-1, *x);
      } else if (p.type == ParamType::kVec2) {
        if (const Vec2* x = std::get_if<Vec2>(&v))
          for (int c = 0; c < 2; ++c) add(c, (*x)[c]);
      } else if (p.type == ParamType::kVec3) {
        if (const Vec3* x = std::get_if<Vec3>(&v))
          for (int c = 0; c < 3; ++c) add(c, (*x)[c]);
      }
    }
  }
  return out;
}

std::shared_ptr<Model> with_parameters(const Model& model, const ParameterValues& values,
                                       const ModelSpec::FunctionCopy& copy) {
  if (values.empty()) return nullptr;
  if (!model.finalized()) throw ModelError("parameters: the model is not compiled");
  const std::vector<ParameterInfo> table = parameters(model);
  // every name known and every value finite, before anything is built
  std::map<std::string, std::vector<const ParameterInfo*>> by_element;
  for (const auto& [name, value] : values) {
    const ParameterInfo* found = nullptr;
    for (const ParameterInfo& p : table)
      if (p.name == name) found = &p;
    if (!found) {
      std::string known;
      for (size_t k = 0; k < table.size() && k < 60; ++k) known += (k ? ", " : "") + table[k].name;
      if (table.size() > 60) known += ", ... (" + std::to_string(table.size()) + " in all)";
      throw ModelError("no parameter '" + name + "'; " +
                       (table.empty() ? std::string("the model has none") : "the parameters are " + known));
    }
    if (!std::isfinite(value)) throw ModelError("parameter '" + name + "' must be finite, got " + to_text(value));
    by_element[found->element].push_back(found);
  }
  auto out = std::make_shared<Model>();
  out->set_dimension(model.dimension());
  if (model.given_gravity()) out->set_gravity(*model.given_gravity());
  for (const GivenElement& e : model.given_elements()) {
    Args args = with_copies(e.args, copy);
    if (auto it = by_element.find(e.name); it != by_element.end())
      for (const ParameterInfo* p : it->second) {
        const double x = values.at(p->name);
        Value v = args.get(p->key);
        if (p->component < 0)
          v = x;
        else if (Vec2* v2 = std::get_if<Vec2>(&v))
          (*v2)[p->component] = x;
        else if (Vec3* v3 = std::get_if<Vec3>(&v))
          (*v3)[p->component] = x;
        args.set(p->key, v);
      }
    add_element(*out, e.name, args);
  }
  out->finalize();
  // numbers do not change what the model is made of
  if (out->n_coordinates() != model.n_coordinates() || out->n_constraints() != model.n_constraints() ||
      out->jacobian_pattern().nonZeros() != model.jacobian_pattern().nonZeros() ||
      out->inputs().size() != model.inputs().size() || out->run_state_size() != model.run_state_size())
    throw ModelError("parameters: the values given change the model's structure (its coordinates or equations)");
  return out;
}

}  // namespace lagmb
