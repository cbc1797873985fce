// Contact between collision shapes in space: how users add one (registry.hpp).
#include "lagmb/elements/spatial_contact.hpp"

#include <cmath>
#include <utility>

#include "elements/build.hpp"

namespace lagmb {

namespace {

/// Finds the pair's geometry in the collision table (the shapes swapped
/// where the table has them the other way round) and adds the element to
/// the forces and the events, sharing one offset of run state.
void build_spatial_contact(Model& m, const std::string& name, const Args& a) {
  const std::string label = build::label(a, name);
  CollisionShape sa = a.shape("shape_a"), sb = a.shape("shape_b");
  sa.check(label + ": shape_a");
  sb.check(label + ": shape_b");
  bool swapped = false;
  const collision::Pair* pair = collision::find_pair(sa.kind, sb.kind);
  if (!pair && (pair = collision::find_pair(sb.kind, sa.kind))) {
    std::swap(sa, sb);
    swapped = true;
  }
  if (!pair)
    throw ModelError(label + ": lagmb has no contact between a " + shape_kind_name(sa.kind) + " and a " +
                     shape_kind_name(sb.kind) + " (the pairs: " + collision::known_pairs() + ")");
  SpatialContact c = build::joining<SpatialContact>(m, name, sa.body, sb.body);
  c.shape_a = std::move(sa);
  c.shape_b = std::move(sb);
  c.radius_a = c.shape_a.bounding_radius();
  c.radius_b = c.shape_b.bounding_radius();
  c.pair = pair;
  c.swapped = swapped;
  c.points = pair->points(c.shape_a, c.shape_b);
  c.law = build::contact_law(a, label);
  c.law.static_friction = a.optional_real("static_friction").value_or(c.law.friction);
  if (!(c.law.static_friction >= c.law.friction) || !std::isfinite(c.law.static_friction))
    throw ModelError(label + ": static_friction must be finite and at least friction (" + to_text(c.law.friction) +
                     "), got " + to_text(c.law.static_friction));
  // a pair of vertices against a surface holds in place where it sticks; a
  // round shape rolls over its points (its friction regularized only)
  c.sticks = pair->anchored && c.law.static_friction > 0.0;
  m.reserve_run_state(c);  // one offset for every entry of the same contact
  m.add_event_element(c, false);
  if (c.sticks) m.add_constraint(c, false);
  m.add_force_element(std::move(c));
}

}  // namespace

KindInfo spatial_contact_kind() {
  KindInfo k = build::kind("spatial_contact")
      .method("add_contact")
      .table("forces")
      .type("contact")
      .role(Role::kContact)
      .in_space()
      .doc("Contact between two collision shapes (Model.add_shape) on different bodies (or one on the ground): "
           "the pair's geometry gives contact points (a sphere 1, a capsule's ends 2, a box's corners 8, a "
           "convex hull's vertices), each with penetration d > 0 pressed by k d^1.5 (1 + c d' / v_impact) along "
           "the normal (Hunt-Crossley damping with c (1 + e) = ln((1 + c) / (1 - c e)): an impact under the "
           "contact force alone rebounds at exactly e times its speed; v_impact the approach speed at the "
           "point's onset, at least 1e-3 m/s) and Coulomb friction -mu F_n v_t / "
           "sqrt(|v_t|^2 + v_s^2) against the slip velocity v_t in the tangent plane. Each point's onset and "
           "release is an event (Result.events) where the integrator restarts. Vertices against a plane (a box's "
           "corners, a hull's) stick: where every pressing point slips slower than v_s and the friction needed is "
           "within static_friction times F_n, three constraint rows hold the contact in place (its events 'stick' "
           "and 'slip').")
      .params({param::shape("shape_a", "the first shape"), param::shape("shape_b", "the second shape")})
      .build(build_spatial_contact);
  for (Param& p : build::contact_law_params()) k.params.push_back(std::move(p));
  k.params.push_back(param::optional_real("static_friction", "",
                                          "mu_s, what a stuck contact holds (default: friction; at least friction)"));
  return k;
}

}  // namespace lagmb
