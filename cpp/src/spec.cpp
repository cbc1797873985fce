// ModelSpec (spec.hpp): the description, checked as it grows, compiled on demand.
#include "lagmb/spec.hpp"

#include "lagmb/model.hpp"

namespace lagmb {

void ModelSpec::set_gravity(Vec2 g) {
  if (!std::isfinite(g.x()) || !std::isfinite(g.y())) throw ModelError("gravity is not finite: " + to_text(g));
  gravity_ = g;
  draft_.reset();
  compiled_.reset();
}

std::shared_ptr<Model> ModelSpec::rebuild() const {
  auto model = std::make_shared<Model>();
  if (gravity_) model->set_gravity(*gravity_);
  for (const Element& e : elements_) add_element(*model, e.name, e.args);
  return model;
}

void ModelSpec::add(const std::string& name, Args args) {
  // build into an open model of our own (a copy of this spec, or compile(),
  // may hold the one we had)
  if (!draft_ || draft_.use_count() > 1 || draft_->finalized()) draft_ = rebuild();
  try {
    add_element(*draft_, name, args);
  } catch (...) {
    draft_.reset();  // it may hold part of the element: rebuilt when next needed
    throw;
  }
  elements_.push_back({name, std::move(args)});
  compiled_.reset();
}

std::shared_ptr<const Model> ModelSpec::compile() const {
  if (!compiled_) {
    std::shared_ptr<Model> model =
        draft_ && draft_.use_count() == 1 && !draft_->finalized() ? std::move(draft_) : rebuild();
    draft_.reset();
    model->finalize();
    compiled_ = std::move(model);
  }
  return compiled_;
}

const Model& ModelSpec::draft() const {
  if (draft_) return *draft_;
  if (compiled_) return *compiled_;
  draft_ = rebuild();
  return *draft_;
}

}  // namespace lagmb
