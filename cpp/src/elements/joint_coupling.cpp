// The spatial kind "joint_coupling": how users add it (registry.hpp).
#include "lagmb/elements/joint_coupling.hpp"

#include <cmath>

#include "elements/build.hpp"

namespace lagmb {

namespace {

void build_joint_coupling(Model& m, const std::string& name, const Args& a) {
  const std::string label = build::label(a, name);
  const std::string& follower = a.text("joint"), &leader = a.text("leader");
  if (follower == leader) throw ModelError(label + ": joint and leader are both '" + follower + "'");
  const build::JointOf b = build::joint_coordinate(m, follower, label);
  const build::JointOf l = build::joint_coordinate(m, leader, label);
  for (const auto* j : {&b, &l})
    if (j->turns && j->slides)
      throw ModelError(label + ": '" + (j == &b ? follower : leader) +
                       "' turns and slides (a cylindrical joint); a coupling relates a revolute's angle or a "
                       "translational's slide");
  JointCoupling e = build::joining<JointCoupling>(m, name, b.body_i, b.body_j);
  e.leader = {l.body_i, l.body_j};
  e.multiplier = a.real("multiplier");
  e.offset = a.real("offset");
  if (!std::isfinite(e.multiplier) || e.multiplier == 0.0)
    throw ModelError(label + ": multiplier must be finite and nonzero, got " + to_text(e.multiplier));
  if (!std::isfinite(e.offset)) throw ModelError(label + ": offset must be finite, got " + to_text(e.offset));
  // each angle continuous through its joint's turns
  e.a = build::continuous_reading(m, leader, l);
  e.b = build::continuous_reading(m, follower, b);
  m.add_constraint(std::move(e));
}

}  // namespace

KindInfo joint_coupling_kind() {
  return build::kind("joint_coupling")
      .method("add_joint_coupling")
      .table("joints")
      .type("coupling")
      .role(Role::kJoint)
      .in_space()
      .doc("Couples two joints: the coordinate s of `joint` (a revolute's angle or a translational's slide) follows "
           "the `leader`'s, s = multiplier s_leader + offset (a URDF <mimic>, an MJCF <joint> equality; a gear or "
           "a belt between two joints' axes). One equation over the four bodies of the two joints; its reaction "
           "is the torque (force) it applies along joint's coordinate on joint's second body. Angles count "
           "whole turns: the joints may turn any number of times.")
      .params({param::joint("the joint that follows (a revolute or translational joint)"),
               param::joint("leader", "the joint it follows"),
               param::real("multiplier", 1.0, "1", "m in s = m s_leader + offset (rad/rad, m/m, rad/m or m/rad)"),
               param::real("offset", 0.0, "rad or m", "the offset s0")})
      .build(build_joint_coupling);
}

}  // namespace lagmb
