#include "lagmb/assembly/analysis.hpp"

#include <string>

#include "lagmb/model/coordinates.hpp"

namespace lagmb {

std::string coordinate_label(const Model& model, int coord) {
  const Body& b = model.body_of_coordinate(coord);
  return "body '" + b.name + "' " + body_coordinate_name(b, coord - b.first_coord);
}

std::vector<std::pair<int, double>> turning_coordinates(const Model& model) {
  std::vector<std::pair<int, double>> out;
  for (const Body& b : model.bodies()) {
    if (b.spatial)
      for (int i = 3; i < 7; ++i) out.emplace_back(b.first_coord + i, 2.0);
    else if (!b.particle)
      out.emplace_back(b.angle_coord(), 1.0);
  }
  return out;
}

}  // namespace lagmb
