#include "lagmb/assembly/analysis.hpp"

#include <string>

namespace lagmb {

std::string coordinate_label(const Model& model, int coord) {
  const Body& b = model.body_of_coordinate(coord);
  // planar (x, y, angle), particle (x, y), spatial (r, Euler parameters p)
  static const char* planar[] = {"x", "y", "angle"};
  static const char* spatial[] = {"x", "y", "z", "e0", "e1", "e2", "e3"};
  const int k = coord - b.first_coord;
  if (k < 0 || k >= b.n_coordinates()) return "coordinate " + std::to_string(coord);
  return "body '" + b.name + "' " + (b.spatial ? spatial : planar)[k];
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
