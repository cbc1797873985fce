// Gear pair: how users add one (registry.hpp).
#include "lagmb/elements/gear.hpp"

#include "elements/build.hpp"

namespace lagmb {

namespace {

/// Pitch radii from the centre distance D: external (ratio < 0) r_i + r_j
/// = D, internal |r_i - r_j| = D, with r_i = |ratio| r_j.
void build_gear(Model& m, const std::string& name, const Args& a) {
  const std::string label = build::label(a, name);
  GearPair g = build::joining<GearPair>(m, name, a.body("body_i"), a.body("body_j"));
  for (int b : {g.body_i, g.body_j}) build::require_rigid(m, b, label, "cannot be a gear (it has no angle)");
  const double ratio = a.real("ratio");
  if (ratio == 0.0 || ratio == 1.0)
    throw ModelError(label + ": ratio must be finite, non-zero and not 1, got " + to_text(ratio));
  for (auto [b, key] : {std::pair{g.body_i, "center_i"}, std::pair{g.body_j, "center_j"}})
    if (b == kGround && !a.given(key))
      throw ModelError(label + ": a gear on the ground needs its centre (" + key + ")");
  const Vec2 ci = a.optional_vec2("center_i").value_or(m.initial_position(g.body_i));
  const Vec2 cj = a.optional_vec2("center_j").value_or(m.initial_position(g.body_j));
  const double D = (cj - ci).norm();
  if (!(D > 0)) throw ModelError(label + ": the gear centres coincide at " + to_text(ci));
  g.c_i = m.local_point(g.body_i, ci);
  g.c_j = m.local_point(g.body_j, cj);
  const double r = std::abs(ratio);
  g.s = ratio < 0 ? 1.0 : -1.0;
  g.r_j = ratio < 0 ? D / (r + 1.0) : D / std::abs(r - 1.0);
  g.r_i = r * g.r_j;
  Local6 c0;
  c0 << m.initial_position(g.body_i), m.initial_angle(g.body_i), m.initial_position(g.body_j),
      m.initial_angle(g.body_j);
  g.c0 = g.rolled(c0);
  m.add_constraint(std::move(g));
}

}  // namespace

KindInfo gear_kind() {
  return build::kind("gear")
      .method("add_gear")
      .table("joints")
      .type("gear")
      .role(Role::kJoint)
      .doc("Gear pair with omega_j / omega_i = ratio while the centres stay put (negative: external, "
           "positive: internal); pitch radii from the initial centre distance.")
      .params({
          param::body("body_i", "the first gear"),
          param::body("body_j", "the second gear"),
          param::real("ratio", "", "omega_j / omega_i with the centres fixed"),
          param::optional_point("center_i", {"body_i"}, "centre of gear i (default: its centre of mass; "
                                                        "required on the ground)"),
          param::optional_point("center_j", {"body_j"}, "centre of gear j (default: its centre of mass; "
                                                        "required on the ground)"),
      })
      .build(build_gear);
}

}  // namespace lagmb
