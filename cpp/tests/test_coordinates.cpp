// What a model says about its coordinates and elements by its kinds
// (lagmb/model/coordinates.hpp, Model::given_kind): the names and units of q as
// Python's Model.coordinate_names and the FMU give them, and each joint
// kind's declared coordinate (KindInfo::coordinate) agreeing with the
// coordinate its equations have (ConstraintGroupBase::coordinate).
#include <string>
#include <vector>

#include "check.hpp"
#include "lagmb/model/coordinates.hpp"
#include "lagmb/run/outputs.hpp"
#include "models.hpp"

using namespace lagmb_test;

namespace {

/// An angle, a slide, both or none, as the group's coordinate() has it.
CoordinateKind equations_coordinate(const Model& model, const std::string& name) {
  const ElementRef& r = model.find(name);
  if (r.type != ElementRef::kConstraint) return CoordinateKind::kNone;
  const auto c = model.constraint_groups()[r.group]->coordinate(r.index);
  if (!c) return CoordinateKind::kNone;
  if (c->turns && c->slides) return CoordinateKind::kAngleAndSlide;
  return c->turns ? CoordinateKind::kAngle : CoordinateKind::kSlide;
}

}  // namespace

TEST_CASE(planar_names_are_x_y_angle_and_a_particle_has_no_angle) {
  ModelSpec spec;
  spec.add("body", "rod", {{"mass", 1.0}, {"inertia", 0.1}, {"position", Vec2(0.5, 0.0)}});
  spec.add("particle", "bob", {{"mass", 0.5}, {"position", Vec2(1.0, 0.0)}});
  spec.add("revolute", "pin", {{"body_i", "ground"}, {"body_j", "rod"}, {"at", Vec2(0.0, 0.0)}});
  spec.add("distance", "link", {{"body_i", "rod"}, {"body_j", "bob"}, {"point_i", Vec2(0.9, 0.0)},
                                {"point_j", Vec2(1.0, 0.0)}});
  const auto model = spec.compile();
  const std::vector<std::string> want = {"rod.x", "rod.y", "rod.angle", "bob.x", "bob.y"};
  CHECK(coordinate_names(*model) == want);
  CHECK(coordinate_units(*model) == std::vector<std::string>({"m", "m", "rad", "m", "m"}));
  CHECK(coordinate_label(*model, 2) == "body 'rod' angle");
  CHECK(coordinate_label(*model, 4) == "body 'bob' y");
  CHECK_THROWS(ModelError, body_coordinate_name(model->bodies()[1], 2), "has no coordinate 2");
}

TEST_CASE(spatial_names_are_the_position_then_the_euler_parameters) {
  const auto model = spatial_pendulum();
  const std::vector<std::string> want = {"rod.x", "rod.y", "rod.z", "rod.e0", "rod.e1", "rod.e2", "rod.e3"};
  CHECK(coordinate_names(*model) == want);
  CHECK(coordinate_units(*model) == std::vector<std::string>({"m", "m", "m", "", "", "", ""}));
  CHECK(coordinate_label(*model, 5) == "body 'rod' e2");
  CHECK(is_body_coordinate_name("angle") && is_body_coordinate_name("e3") && !is_body_coordinate_name("mass"));
}

TEST_CASE(given_kind_gives_each_element_its_registry_kind) {
  ModelSpec spec;
  spec.add("body", "rod", {{"mass", 1.0}, {"inertia", 0.1}, {"position", Vec2(0.5, 0.0)}});
  spec.add("revolute", "pin", {{"body_i", "ground"}, {"body_j", "rod"}, {"at", Vec2(0.0, 0.0)}});
  spec.add("joint_driver", "motor", {{"joint", "pin"}, {"f", constant(0.0)}});
  const auto model = spec.compile();
  CHECK(model->given_kind("rod")->role == Role::kBody);
  CHECK(model->given_kind("pin")->name == "revolute" && model->given_kind("pin")->role == Role::kJoint);
  CHECK(model->given_kind("motor")->name == "joint_driver" && model->given_kind("motor")->role == Role::kDriver);
  CHECK_THROWS(ModelError, model->given_kind("nothing"), "no body or element named 'nothing'");
}

// The output names of a reaction end in these ("hinge.reaction.torque.x"),
// one per column of reactions().
TEST_CASE(a_reaction_has_three_components_in_the_plane_and_six_in_space) {
  const OutputView none;
  CHECK(reaction_components(2) == std::vector<std::string>({"x", "y", "torque"}));
  CHECK(int(reaction_components(3).size()) == 6 && reaction_components(3)[3] == "torque.x");
  CHECK(reactions(*pendulum(), "pin", none).cols() == int(reaction_components(2).size()));
  CHECK(reactions(*spatial_pendulum(), "pin", none).cols() == int(reaction_components(3).size()));
  CHECK_THROWS(ModelError, reaction_components(4), "dimension must be 2 or 3");
}

// Python (Result.joint, JointSpace) and the FMU's units read the joint
// coordinate from the kind: it must be the one the equations have.
TEST_CASE(each_joint_kind_declares_the_coordinate_its_equations_have) {
  const auto crank = slider_crank();
  for (const std::string name : {"O", "guide"}) {
    CHECK(crank->given_kind(name)->coordinate == equations_coordinate(*crank, name));
    CHECK(crank->given_kind(name)->coordinate != CoordinateKind::kNone);
  }
  for (const std::string kind : {"spatial_revolute", "spatial_translational", "cylindrical"}) {
    ModelSpec spec(3);
    spec.add("spatial_body", "b", {{"mass", 2.0}, {"inertia", Vec3(0.3, 0.2, 0.4)}, {"position", Vec3(0.8, -0.4, 0.5)}});
    spec.add(kind, "joint", {{"body_i", "ground"}, {"body_j", "b"}, {"at", Vec3(0.5, 0.0, 0.4)},
                             {"axis", Vec3(0.2, -0.3, 0.9)}});
    const auto model = spec.compile();
    CHECK(model->given_kind("joint")->coordinate == equations_coordinate(*model, "joint"));
    CHECK(model->given_kind("joint")->coordinate != CoordinateKind::kNone);
  }
  ModelSpec spec(3);
  spec.add("spatial_body", "b", {{"mass", 2.0}, {"inertia", Vec3(0.3, 0.2, 0.4)}, {"position", Vec3(0.8, -0.4, 0.5)}});
  spec.add("spherical", "ball", {{"body_i", "ground"}, {"body_j", "b"}, {"at", Vec3(0.5, 0.0, 0.4)}});
  spec.add("universal", "cross", {{"body_i", "ground"}, {"body_j", "b"}, {"at", Vec3(0.5, 0.0, 0.4)},
                                  {"axis_i", Vec3(1.0, 0.0, 0.0)}, {"axis_j", Vec3(0.0, 1.0, 0.0)}});
  const auto model = spec.compile();
  for (const std::string name : {"ball", "cross"}) {
    CHECK(model->given_kind(name)->coordinate == CoordinateKind::kNone);
    CHECK(equations_coordinate(*model, name) == CoordinateKind::kNone);
  }
}

LAGMB_TEST_MAIN()
