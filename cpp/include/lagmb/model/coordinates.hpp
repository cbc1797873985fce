// The names of a model's coordinates q: one table for every place that
// names them (messages, the FMU's variables, Model.coordinate_names in Python),
// and which of them turn.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "lagmb/model/body.hpp"

namespace lagmb {

class Model;

/// The name of coordinate k (0 <= k < body.n_coordinates()) within its
/// body: x, y, angle for a planar body (a particle has x, y); x, y, z and
/// the Euler parameters e0 .. e3 (w, x, y, z) for a spatial one.
const char* body_coordinate_name(const Body& body, int k);

/// The unit of that coordinate: "rad" for an angle, "m" for a position,
/// "" for an Euler parameter.
const char* body_coordinate_unit(const Body& body, int k);

/// Whether `name` is the name of a coordinate within some body ("x",
/// "angle", "e2", ...): a parameter of that name would shadow it.
bool is_body_coordinate_name(const std::string& name);

/// The names of a finalized model's coordinates, in the order of q:
/// "<body>.<coordinate>" ("rod.x", "rod.y", "rod.angle", "base.e0", ...).
std::vector<std::string> coordinate_names(const Model& model);
/// Their units, in the same order (body_coordinate_unit).
std::vector<std::string> coordinate_units(const Model& model);

/// "body 'rod' angle": the body and the role of coordinate `coord` of q,
/// as messages name it.
std::string coordinate_label(const Model& model, int coord);

/// The coordinates of q that turn, with the angle per unit of each: a
/// planar body's angle (1) and a spatial body's Euler parameters (2: a turn
/// by theta moves p by about theta / 2). What the step limits of assembly,
/// equilibrium and kinematic analysis bound.
std::vector<std::pair<int, double>> turning_coordinates(const Model& model);

}  // namespace lagmb
