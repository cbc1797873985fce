// The model's coordinates as the analyses and their messages see them:
// which turn (the step limits of the position solves) and what each is.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "lagmb/model/data.hpp"

namespace lagmb {

/// The coordinates of q that turn, with the angle per unit of each: a
/// planar body's angle (1) and a spatial body's Euler parameters (2: a turn
/// by theta moves p by about theta / 2). What the step limits of assembly,
/// equilibrium and kinematic analysis bound.
std::vector<std::pair<int, double>> turning_coordinates(const Model& model);

/// "body 'rod' angle": the body and the role of coordinate `coord` of q.
std::string coordinate_label(const Model& model, int coord);

}  // namespace lagmb
