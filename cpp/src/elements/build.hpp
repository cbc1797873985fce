// What the builders of element kinds share (registry.hpp): the checks every
// kind makes of its bodies, and the conversion of the initial
// configuration's global points and directions to body axes. Each builder
// lives in cpp/src/elements/<kind>.cpp next to its kind's declaration.
#pragma once

#include <array>
#include <string>

#include "lagmb/elements/projected_offset.hpp"
#include "lagmb/model/model.hpp"
#include "lagmb/model/registry.hpp"

namespace lagmb::build {

/// How messages name an element: "<kind> '<name>'" ("rack pinion 'r1'").
std::string label(const Args& args, const std::string& name);

/// A new element of Kind called `name` acting between body_i and body_j
/// (kGround for a single-body element's other side); ModelError unless both
/// exist and differ.
template <class Kind>
Kind joining(const Model& m, const std::string& name, int body_i, int body_j) {
  m.check_pair(name, body_i, body_j);
  Kind e;
  e.name = name;
  e.body_i = body_i;
  e.body_j = body_j;
  return e;
}

/// What an element follows: `f`, or the run's value of the model's input
/// `f` is (added before the builder runs; Drive::input its slot).
Drive drive(const Model& m, TimeFunctionPtr f);
std::array<Drive, 3> drive_triple(const Model& m, const std::array<TimeFunctionPtr, 3>& f);

/// ModelError "'<element>': <what>" unless x is finite and positive.
void require_positive(double x, const std::string& element, const char* what);
/// ModelError naming `element` unless 4 x^2 is finite (a length squared in an equation).
void require_squarable(double x, const std::string& element, const char* what);
/// ModelError "'<element>': <what>" unless x is finite and >= 0.
void require_nonnegative(double x, const std::string& element, const char* what);

/// A body that takes this element needs an angle (particles have none).
void require_rigid(const Model& m, int body, const std::string& element, const char* why);
/// On a particle the element's point must be the particle itself.
void require_on_particle(const Model& m, int body, Vec2 point, const std::string& element);

/// A unit direction, given globally in the initial configuration, in the
/// body's axes; ModelError for a zero vector.
Vec2 local_direction(const Model& m, int body, Vec2 direction, const std::string& element);
/// The line through `at` along `axis` fixed in body i, as the offset from it
/// measured across the line: w = axis turned +90 deg (body i's axes),
/// s_i, s_j = `at` in each body's axes.
ProjectedOffset across_line(const Model& m, int body_i, int body_j, Vec2 at, Vec2 axis,
                            const std::string& element);

/// The scalar coordinate of a joint that has one: a revolute's relative
/// angle phi_j - phi_i, or a translational's slide along its axis (0 in the
/// initial configuration). Drivers, friction and stops act on it.
struct JointCoordinate {
  ElementRef joint;        // the joint element
  int body_i = kGround, body_j = kGround;
  bool slide = false;      // translational: the slide along `along`
  ProjectedOffset along;   // slide: w = the axis in body i's axes
};
/// The coordinate of the joint called `joint`; ModelError naming `element`
/// if there is no such joint or it has no coordinate.
JointCoordinate joint_coordinate(const Model& m, const std::string& joint, const std::string& element);

}  // namespace lagmb::build
