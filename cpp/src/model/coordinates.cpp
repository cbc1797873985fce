// The names of a model's coordinates and which turn (coordinates.hpp).
#include "lagmb/model/coordinates.hpp"

#include "lagmb/errors.hpp"
#include "lagmb/model/model.hpp"

namespace lagmb {

namespace {

// in the order of each body's block of q (body.hpp)
constexpr const char* kPlanar[] = {"x", "y", "angle"};  // a particle: the first two
constexpr const char* kSpatial[] = {"x", "y", "z", "e0", "e1", "e2", "e3"};

}  // namespace

const char* body_coordinate_name(const Body& body, int k) {
  if (k < 0 || k >= body.n_coordinates())
    throw ModelError("body '" + body.name + "' has no coordinate " + std::to_string(k) + " (it has " +
                     std::to_string(body.n_coordinates()) + ")");
  return (body.spatial ? kSpatial : kPlanar)[k];
}

const char* body_coordinate_unit(const Body& body, int k) {
  const std::string name = body_coordinate_name(body, k);
  return name == "angle" ? "rad" : name[0] == 'e' ? "" : "m";
}

bool is_body_coordinate_name(const std::string& name) {
  for (const char* c : kPlanar)
    if (name == c) return true;
  for (const char* c : kSpatial)
    if (name == c) return true;
  return false;
}

std::vector<std::string> coordinate_names(const Model& model) {
  if (!model.finalized()) throw ModelError("coordinate_names: the model is not finalized");
  std::vector<std::string> out(size_t(model.n_coordinates()));
  for (const Body& b : model.bodies())
    for (int k = 0; k < b.n_coordinates(); ++k) out[size_t(b.first_coord + k)] = b.name + "." + body_coordinate_name(b, k);
  return out;
}

std::vector<std::string> coordinate_units(const Model& model) {
  if (!model.finalized()) throw ModelError("coordinate_units: the model is not finalized");
  std::vector<std::string> out(size_t(model.n_coordinates()));
  for (const Body& b : model.bodies())
    for (int k = 0; k < b.n_coordinates(); ++k) out[size_t(b.first_coord + k)] = body_coordinate_unit(b, k);
  return out;
}

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
