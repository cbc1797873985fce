#include "lagmb/model/gravity.hpp"

#include "lagmb/model/model.hpp"

namespace lagmb {

void Gravity::place(const Model& model) {
  bodies_.clear();
  for (const auto& b : model.bodies()) bodies_.push_back({b.first_coord, b.mass, b.spatial ? 3 : 2});
}

}  // namespace lagmb
