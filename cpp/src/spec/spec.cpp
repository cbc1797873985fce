// ModelSpec (spec.hpp): the description, checked as it grows, compiled on demand.
#include "lagmb/spec/spec.hpp"

#include "lagmb/model/model.hpp"

namespace lagmb {

ModelSpec::ModelSpec(int dimension) : dimension_(dimension) {
  Model().set_dimension(dimension);  // ModelError unless 2 or 3
}

void ModelSpec::set_gravity(Vec2 g) {
  if (dimension_ != 2)
    throw ModelError("gravity of a spatial model has three components (x, y, z), got " + lagmb::to_text(g));
  set_gravity(Vec3(g.x(), g.y(), 0.0));
}

void ModelSpec::set_gravity(Vec3 g) {
  Model check;  // the Model's checks (finite; z = 0 in the plane)
  check.set_dimension(dimension_);
  check.set_gravity(g);
  gravity_ = g;
  draft_.reset();
  compiled_.reset();
}

Args with_copies(const Args& args, const ModelSpec::FunctionCopy& copy) {
  if (!copy) return args;
  Args out(args.kind());
  for (const auto& [key, value] : args.values()) {
    if (const auto* f = std::get_if<TimeFunctionPtr>(&value))
      out.set(key, copy(*f));
    else if (const auto* fs = std::get_if<std::pair<TimeFunctionPtr, TimeFunctionPtr>>(&value))
      out.set(key, std::make_pair(copy(fs->first), copy(fs->second)));
    else if (const auto* f3 = std::get_if<std::array<TimeFunctionPtr, 3>>(&value))
      out.set(key, std::array<TimeFunctionPtr, 3>{copy((*f3)[0]), copy((*f3)[1]), copy((*f3)[2])});
    else
      out.set(key, value);
  }
  return out;
}

namespace {

/// Whether `copy` leaves every time function of `elements` as it is (null,
/// or the binding's copy of a model without Python functions).
bool copies_nothing(const std::vector<ModelSpec::Element>& elements, const ModelSpec::FunctionCopy& copy) {
  if (!copy) return true;
  auto same = [&](const TimeFunctionPtr& f) { return !f || copy(f).get() == f.get(); };
  for (const ModelSpec::Element& e : elements)
    for (const auto& [key, value] : e.args.values()) {
      if (const auto* f = std::get_if<TimeFunctionPtr>(&value); f && !same(*f)) return false;
      if (const auto* fs = std::get_if<std::pair<TimeFunctionPtr, TimeFunctionPtr>>(&value);
          fs && !(same(fs->first) && same(fs->second)))
        return false;
      if (const auto* f3 = std::get_if<std::array<TimeFunctionPtr, 3>>(&value);
          f3 && !(same((*f3)[0]) && same((*f3)[1]) && same((*f3)[2])))
        return false;
    }
  return true;
}

}  // namespace

std::shared_ptr<Model> ModelSpec::rebuild(const FunctionCopy& copy) const {
  auto model = std::make_shared<Model>();
  model->set_dimension(dimension_);
  if (gravity_) model->set_gravity(*gravity_);
  for (const Element& e : elements_) add_element(*model, e.name, with_copies(e.args, copy));
  element_builds_ += long(elements_.size());
  return model;
}

void ModelSpec::add(const std::string& name, Args args) {
  // build into an open model of our own (a copy of this spec may share the
  // one we had; the one compiled last is finalized)
  if (!draft_ || draft_.use_count() > 1 || draft_->finalized()) draft_ = rebuild();
  // room for one more (doubling, so that adds stay amortized O(1)), so that
  // nothing throws after the draft took the element
  if (elements_.size() == elements_.capacity()) elements_.reserve(2 * elements_.size() + 1);
  try {
    add_element(*draft_, name, args);
  } catch (...) {
    draft_.reset();  // it may hold part of the element: rebuilt when next needed
    throw;
  }
  ++element_builds_;
  elements_.push_back({name, std::move(args)});
  compiled_.reset();
}

void ModelSpec::add(const std::string& kind, const std::string& name, std::initializer_list<Given> values) {
  Args args(find_kind(kind));
  for (const Given& g : values) args.set(g.key, g.value);
  add(name, std::move(args));
}

std::shared_ptr<Model> ModelSpec::build(const FunctionCopy& copy) const {
  std::shared_ptr<Model> model;
  if (draft_ && draft_.use_count() == 1 && !draft_->finalized() && copies_nothing(elements_, copy))
    model = draft_;  // the elements built as they were added: not built again
  else
    model = rebuild(copy);
  model->finalize();
  // answers draft()'s questions until the next add (which builds a new draft)
  draft_ = model;
  return model;
}

std::shared_ptr<const Model> ModelSpec::compile(const FunctionCopy& copy) const {
  if (!compiled_) compiled_ = build(copy);
  return compiled_;
}

ModelSpec ModelSpec::copied(const FunctionCopy& copy) const {
  ModelSpec out(dimension_);  // (its draft is built when first needed)
  out.gravity_ = gravity_;
  for (const Element& e : elements_) out.elements_.push_back({e.name, with_copies(e.args, copy)});
  return out;
}

const Model& ModelSpec::draft() const {
  if (!draft_) draft_ = rebuild();
  return *draft_;
}

}  // namespace lagmb
