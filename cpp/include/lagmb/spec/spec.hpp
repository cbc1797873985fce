// The editable description of a model, compiled into an immutable Model
// (as MuJoCo separates mjSpec from mjModel).
#pragma once

#include <functional>
#include <initializer_list>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lagmb/model/registry.hpp"
#include "lagmb/types.hpp"

namespace lagmb {

/// A model as the user describes it: gravity and the elements in the order
/// added, each a kind of the registry, a name and its values. Copying a
/// spec copies the description (the time functions are shared); a copy is
/// edited independently.
///
/// Each add() is checked at once against what came before (names, bodies,
/// joints, values), so an error names the element that causes it. compile()
/// gives the immutable Model that kernels and runs read: coordinates and
/// rows numbered, patterns and slots built, linear in the model's size and
/// without solver calls (Model::finalize). The compiled Model is kept until
/// the spec changes; it is never changed, so several threads may run it.
/// A spec itself is edited by one thread at a time.
/// One value given by its parameter's name, for ModelSpec::add from C++:
/// {"mass", 1.0}, {"at", Vec2(0, 0)}, {"body_j", "rod"}. Bodies are given
/// by name ("ground" for the ground).
struct Given {
  Given(std::string key, double x) : key(std::move(key)), value(x) {}
  Given(std::string key, int x) : key(std::move(key)), value(double(x)) {}
  Given(std::string key, Vec2 x) : key(std::move(key)), value(x) {}
  Given(std::string key, Vec3 x) : key(std::move(key)), value(x) {}
  Given(std::string key, Vec4 x) : key(std::move(key)), value(x) {}
  Given(std::string key, Mat3 x) : key(std::move(key)), value(x) {}
  Given(std::string key, bool x) : key(std::move(key)), value(x) {}
  Given(std::string key, const char* text) : key(std::move(key)), value(std::string(text)) {}
  Given(std::string key, std::string text) : key(std::move(key)), value(std::move(text)) {}
  Given(std::string key, CollisionShape shape) : key(std::move(key)), value(std::move(shape)) {}
  Given(std::string key, TimeFunctionPtr f) : key(std::move(key)), value(std::move(f)) {}
  Given(std::string key, TimeFunctionPtr fx, TimeFunctionPtr fy)
      : key(std::move(key)), value(std::make_pair(std::move(fx), std::move(fy))) {}
  std::string key;
  Value value;
};

class ModelSpec;

class ModelSpec {
 public:
  struct Element {
    std::string name;
    Args args;  // knows its kind
  };

  /// A planar (2, the default) or spatial (3) model: every element kind
  /// must be of its space.
  explicit ModelSpec(int dimension = 2);
  int dimension() const { return dimension_; }

  /// Uniform gravity g (m/s^2); absent until set. (x, y) for a planar model,
  /// (x, y, z) for a spatial one (a planar one takes z = 0).
  void set_gravity(Vec2 g);
  void set_gravity(Vec3 g);
  const std::optional<Vec3>& gravity() const { return gravity_; }

  /// Adds an element of args.kind() called `name`; ModelError if the
  /// element does not fit the model so far (the spec is then unchanged).
  void add(const std::string& name, Args args);
  /// The same with the kind by name (registry.hpp) and its values:
  ///   spec.add("revolute", "pin", {{"body_i", "ground"}, {"body_j", "rod"}, {"at", Vec2(0, 0)}});
  void add(const std::string& kind, const std::string& name, std::initializer_list<Given> values);
  const std::vector<Element>& elements() const { return elements_; }

  /// Gives a compiled model its own copy of a time function (the Python
  /// binding: its own reference to a Python callable, so that the collector
  /// sees each reference once); null: the functions are shared.
  using FunctionCopy = std::function<TimeFunctionPtr(const TimeFunctionPtr&)>;

  /// The compiled, immutable model of the spec as it is now: built from the
  /// description (with `copy` applied to its time functions), finalized,
  /// and kept until the spec changes.
  std::shared_ptr<const Model> compile(const FunctionCopy& copy = nullptr) const;

  /// A new compiled model, not kept (compile() keeps one): the Python
  /// binding gives each compiled model its own Python owner. The model the
  /// adds built (and checked) becomes it, so that each element is built
  /// once, unless `copy` changes a time function or a compiled model took
  /// that one already: then the elements are built again.
  std::shared_ptr<Model> build(const FunctionCopy& copy = nullptr) const;

  /// Elements built into models by this spec so far (by add, and by
  /// rebuilding the description): the cost of describing and compiling.
  long element_builds() const { return element_builds_; }

  /// The description with `copy` applied to its time functions.
  ModelSpec copied(const FunctionCopy& copy) const;

  /// The description as text, the values as given (numbers to 17 digits),
  /// that from_text reads back to a spec that compiles to the same model:
  /// what an FMU carries. ModelError naming the element whose time function
  /// has no text (a Python callable).
  std::string to_text() const;
  /// Reads what to_text wrote; ModelError naming the line that is wrong.
  static ModelSpec from_text(const std::string& text);

  /// The model being built (or, after build, the one built last): the
  /// checks of add() and what an element attaches to (Model::outline,
  /// Model::attachments).
  const Model& draft() const;

 private:
  // a new open Model from the description
  std::shared_ptr<Model> rebuild(const FunctionCopy& copy = nullptr) const;

  int dimension_ = 2;
  std::optional<Vec3> gravity_;
  std::vector<Element> elements_;
  // The open Model holding every element so far (checks each add; a copy of
  // the spec shares it until either adds), and the compiled model.
  mutable std::shared_ptr<Model> draft_;
  mutable std::shared_ptr<const Model> compiled_;
  mutable long element_builds_ = 0;
};

/// The values of `args` with `copy` applied to each time function (null: as they are).
Args with_copies(const Args& args, const ModelSpec::FunctionCopy& copy);

}  // namespace lagmb
