// Assembly kernels: plain functions of (const Model&, Data&).
//
// Each loops over the element groups present in the model; a kind the
// model does not contain has no group and costs nothing.
#pragma once

#include "lagmb/model/data.hpp"

namespace lagmb {

/// d.Phi = Phi(q, t).
void assemble_constraints(const Model& model, Data& d, const double* q, double t);
/// d.Phi_q = Phi_q(q, t), values written in place.
void assemble_jacobian(const Model& model, Data& d, const double* q, double t);
/// d.phi_t = Phi_t(q, t) (zero for a model without time-dependent constraints).
void assemble_phi_t(const Model& model, Data& d, const double* q, double t);
/// d.gamma = -(Phi_q v)_q v - 2 Phi_qt v - Phi_tt.
void assemble_gamma(const Model& model, Data& d, const double* q, const double* v, double t);
/// d.Vq = d(Phi_q v + Phi_t)/dq.
void assemble_velocity_jacobian(const Model& model, Data& d, const double* q, const double* v,
                                double t);
/// d.H = sum_r w_r d2Phi_r/dq2  (= (Phi_q^T w)_q).
void assemble_constraint_hessian(const Model& model, Data& d, const double* q, double t,
                                 const double* w);
/// d.Q = Q(q, v, t).
void assemble_forces(const Model& model, Data& d, const double* q, const double* v, double t);
/// d.Q_q, d.Q_v: exact derivatives of Q (left zero where no force depends on the state).
void assemble_force_derivatives(const Model& model, Data& d, const double* q, const double* v,
                                double t);

/// d.Q += Q_f(q, v, lam): joint friction, which depends on the multipliers
/// (friction_group.hpp). Nothing runs for a model without friction.
void add_friction_forces(const Model& model, Data& d, const double* q, const double* v,
                         const double* lam);
/// d.friction_Q_q, d.friction_Q_v and d.friction_Q_lam (= (dQ_f/dlam)^T, in
/// the pattern of Phi_q): exact derivatives of the friction forces.
void assemble_friction_derivatives(const Model& model, Data& d, const double* q, const double* v,
                                   const double* lam);

/// y += Phi_q^T w (Phi_q from d).
void add_jacobian_transpose_times(const Data& d, const double* w, double* y);
/// y += Phi_q x.
void add_jacobian_times(const Data& d, const double* x, double* y);

// --- the mass matrix (mass.cpp) ---------------------------------------------
// M is block diagonal: constant diagonal entries for planar bodies,
// particles and the centre of mass of spatial bodies, and a 4 x 4 block
// M_p(p) at the Euler parameters of each spatial body
// (elements/spatial_body.hpp). Its values live in d.M, d.M_inv (pattern
// Model::mass_pattern()); the constant entries are written once, by Data's
// constructor (init_mass).

/// Writes the constant entries of d.M and d.M_inv (1/M_ii; 0 where M_ii = 0).
void init_mass(const Model& model, Data& d);
/// d.M = M(q): the spatial bodies' blocks (nothing to do for a planar
/// model). assemble_jacobian calls it: whatever solves with Phi_q at q (the
/// augmented system) finds M at the same q.
void assemble_mass(const Model& model, Data& d, const double* q);
/// d.M_inv = M(q)^-1: the spatial bodies' blocks, for what reads M^-1
/// itself (an impact's mobilities, the force rates' power iteration); the
/// augmented system does not (its Schur complement takes the bodies'
/// constant inverse mass in body rates), so assemble_jacobian leaves it.
void assemble_mass_inverse(const Model& model, Data& d, const double* q);
/// y = M a (M as assembled in d).
void mass_times(const Data& d, const double* a, double* y);
/// y = M^-1 b (as assembled in d).
void mass_inverse_times(const Data& d, const double* b, double* y);
/// d.M_qa = d(M(q) a)/dq (zero for a planar model).
void assemble_mass_derivative(const Model& model, Data& d, const double* q, const double* a);
/// Kinetic energy: 1/2 v^T M v for planar bodies, m r'.r' / 2 + omega'^T J'
/// omega' / 2 for spatial ones.
double kinetic_energy(const Model& model, const double* q, const double* v);
/// Potential energy of the conservative forces at (q, at).
double potential_energy(const Model& model, const double* q, const Instant& at);

}  // namespace lagmb
