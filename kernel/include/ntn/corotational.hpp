// Two-node 3D corotational beam: the internal force under large displacements and rotations with
// small strains, the linear element's natural stiffness (beam.hpp) acting in a frame that follows
// the element. Formulation of Battini & Pacoste (2002), "Co-rotational beam elements with warping
// effects in instability problems", CMAME 191, without warping: corotated frame, local
// rotations, their variation through T_s^-1 and the frame's spin (their G matrix). Crisfield
// (1990), "A consistent co-rotational formulation for non-linear, three-dimensional,
// beam-elements", CMAME 81, builds the frame from the mean of the nodal rotations instead; both
// frames are symmetric in the two nodes. The step calls it for the elements with geometry
// "corotational" (integrator.hpp's corotational stage), in element order.
//
// Conventions. A node's rotation q is its total rotation from the reference configuration,
// spatial: a fibre t0 of the reference is Q t0 now, and a variation is a spatial spin dw,
// dQ = skew(dw) Q. Frames are stored as in BeamData: rows are the local axes in global, so
// local = R global. R0 is the element's reference frame, R_r its corotated frame now.
#pragma once

#include <cstddef>
#include <cstdint>

#include "ntn/beam.hpp"
#include "ntn/model_spec.hpp"
#include "ntn/rotation.hpp"

namespace ntn {

// What the corotational force needs of one element: its reference chord, length and frame, and
// the linear element's constants at the reference length.
struct CorotationalBeam {
  Vector3 chord{};     // X_j - X_i, m
  double length = 0;   // l0 = |X_j - X_i|, m
  Matrix3 rotation{};  // R0, rows: local x, y, z in global (as BeamData::rotation)
  BeamStiffness k;     // beam_stiffness at l0: EA/l0, GJ/l0, a..d per plane
};

// The element's corotated frame, natural deformations and natural forces: local x along the
// chord, rotations measured from the corotated frame.
struct CorotationalLocal {
  Matrix3 frame{};                 // R_r, rows e1, e2, e3 in global
  double length = 0;               // l, m
  double stretch = 0;              // u_l = l - l0, m
  Vector3 theta_i{}, theta_j{};    // deformational rotations (x, y, z local), rad
  double axial = 0;                // N = EA/l0 u_l, tension positive, N
  Vector3 moment_i{}, moment_j{};  // (T, M_y, M_z) conjugate to theta_i, theta_j, N m
  double q2 = 1;                   // |e1 x q|: the frame's footing, 1 undeformed (below)
};

inline ElementCheck corotational_beam(const NodeSpec& a, const NodeSpec& b, const ElementSpec& e,
                                      CorotationalBeam& out) {
  const BeamGeometry g = beam_geometry(a, b, e);
  if (g.check != ElementCheck::kOk) return g.check;
  if (!beam_properties_valid(e)) return ElementCheck::kBadProperty;
  out.chord = {b.x - a.x, b.y - a.y, b.z - a.z};
  out.length = g.length;
  out.rotation = g.rotation;
  out.k = beam_stiffness(e, g.length);
  return ElementCheck::kOk;
}

namespace detail {

// A row-major product A B^T: entry (a, b) is row a of A dot row b of B.
inline Matrix3 times_transpose(const Matrix3& A, const Matrix3& B) {
  Matrix3 C{};
  for (std::size_t a = 0; a < 3; ++a) {
    for (std::size_t b = 0; b < 3; ++b)
      C[3 * a + b] =
          A[3 * a] * B[3 * b] + A[3 * a + 1] * B[3 * b + 1] + A[3 * a + 2] * B[3 * b + 2];
  }
  return C;
}

// A row-major product A B.
inline Matrix3 times(const Matrix3& A, const Matrix3& B) {
  Matrix3 C{};
  for (std::size_t a = 0; a < 3; ++a) {
    for (std::size_t b = 0; b < 3; ++b)
      C[3 * a + b] = A[3 * a] * B[b] + A[3 * a + 1] * B[3 + b] + A[3 * a + 2] * B[6 + b];
  }
  return C;
}

// Current chord x = (X_j - X_i) + (u_j - u_i), its length l = |x|, 1/l, and u_l = l - l0 as
// (l^2 - l0^2)/(l + l0) with l^2 - l0^2 = du . (2 (X_j - X_i) + du): no cancellation of l - l0,
// and a rigid motion gives u_l at the rounding of du, not of l0 (l0 = |X_j - X_i|). 1/l as
// inverse_root(l^2/l0^2)/l0: no root while the strain is under 3 %.
struct Chord {
  Vector3 x{};
  double length = 0, inverse_length = 0, stretch = 0;
};

inline Chord current_chord(const CorotationalBeam& b, const double* ui, const double* uj) {
  const Vector3 du{uj[0] - ui[0], uj[1] - ui[1], uj[2] - ui[2]};
  Chord c;
  c.x = {b.chord[0] + du[0], b.chord[1] + du[1], b.chord[2] + du[2]};
  const double l2_minus_l02 = du[0] * (2.0 * b.chord[0] + du[0]) +
                              du[1] * (2.0 * b.chord[1] + du[1]) +
                              du[2] * (2.0 * b.chord[2] + du[2]);
  const double l2 = dot(c.x, c.x), inv_l0 = 1.0 / b.length;
  c.inverse_length = inverse_root(l2 * inv_l0 * inv_l0) * inv_l0;
  c.length = l2 * c.inverse_length;
  c.stretch = l2_minus_l02 / (c.length + b.length);
  return c;
}

// Corotated frame (Battini & Pacoste 2002): e1 = x/l; with the nodal triads' second axes
// t_i2, t_j2 (columns 1 of T_i, T_j) and their mean q = (t_i2 + t_j2)/2, e3 = e1 x q / |e1 x q|
// and e2 = e3 x e1. Symmetric in the two nodes; needs q off the chord (deformational rotations
// under 90 degrees about local z). |e1 x q| is near 1 while the deformational rotations are
// small: inverse_root.
inline Matrix3 corotated_frame(const Chord& c, const Matrix3& Ti, const Matrix3& Tj) {
  const double inv_l = c.inverse_length;
  const Vector3 e1{c.x[0] * inv_l, c.x[1] * inv_l, c.x[2] * inv_l};
  const Vector3 q{0.5 * (Ti[1] + Tj[1]), 0.5 * (Ti[4] + Tj[4]), 0.5 * (Ti[7] + Tj[7])};
  const Vector3 n = cross(e1, q);
  const double inv_n = inverse_root(dot(n, n));
  const Vector3 e3{n[0] * inv_n, n[1] * inv_n, n[2] * inv_n};
  const Vector3 e2 = cross(e3, e1);
  return {e1[0], e1[1], e1[2], e2[0], e2[1], e2[2], e3[0], e3[1], e3[2]};
}

// Natural forces of the linear element (beam.hpp's constants): N = EA/l0 u_l;
// T = GJ/l0 (theta_xj - theta_xi), -T at node i; per plane M_i = c theta_i + d theta_j,
// M_j = d theta_i + c theta_j (plane x-z: M_y from k.xz; plane x-y: M_z from k.xy). With the
// chord as local x there is no transverse displacement, so a and b do not enter.
inline void natural_forces(const BeamStiffness& k, CorotationalLocal& n) {
  const Vector3& ti = n.theta_i;
  const Vector3& tj = n.theta_j;
  n.axial = k.axial * n.stretch;
  const double t = k.torsion * (tj[0] - ti[0]);
  n.moment_i = {-t, k.xz[2] * ti[1] + k.xz[3] * tj[1], k.xy[2] * ti[2] + k.xy[3] * tj[2]};
  n.moment_j = {t, k.xz[3] * ti[1] + k.xz[2] * tj[1], k.xy[3] * ti[2] + k.xy[2] * tj[2]};
}

// beta times the natural forces of the deformation rates (corotational_force's damping): the
// rates d_l' = B [v_i, w_i, v_j, w_j] with the frame, triads and G terms of the elastic force
// (n, Ri = R_r T_i, Rj, 1/q2, eta = q1/q2, 1/l).
inline CorotationalLocal natural_rates(const CorotationalBeam& b, const CorotationalLocal& n,
                                       const Matrix3& Ri, const Matrix3& Rj, double inv_q2,
                                       double eta, double inv_l, const double* vi, const double* vj,
                                       double beta) {
  double ti[3], tj[3], wi[3], wj[3];  // local: node i's and j's translation and spin rates
  beam_to_local(kGeneralAxes, n.frame, vi, ti), beam_to_local(kGeneralAxes, n.frame, vi + 3, wi);
  beam_to_local(kGeneralAxes, n.frame, vj, tj), beam_to_local(kGeneralAxes, n.frame, vj + 3, wj);
  const double w2 = (ti[2] - tj[2]) * inv_l, w3 = (tj[1] - ti[1]) * inv_l;
  const double w1 = eta * w2 + 0.5 * (Ri[4] * inv_q2 * wi[0] - Ri[1] * inv_q2 * wi[1] +
                                      Rj[4] * inv_q2 * wj[0] - Rj[1] * inv_q2 * wj[1]);
  const Vector3 si{wi[0] - w1, wi[1] - w2, wi[2] - w3}, sj{wj[0] - w1, wj[1] - w2, wj[2] - w3};
  const Vector3 minus_i{-n.theta_i[0], -n.theta_i[1], -n.theta_i[2]};
  const Vector3 minus_j{-n.theta_j[0], -n.theta_j[1], -n.theta_j[2]};
  const Vector3 di = log_tangent_inverse_transpose(minus_i, si);  // T_s^-1(theta_i) (w_i - w_r)
  const Vector3 dj = log_tangent_inverse_transpose(minus_j, sj);
  CorotationalLocal d;
  d.stretch = beta * (tj[0] - ti[0]);
  d.theta_i = {beta * di[0], beta * di[1], beta * di[2]};
  d.theta_j = {beta * dj[0], beta * dj[1], beta * dj[2]};
  natural_forces(b.k, d);
  return d;
}

}  // namespace detail

// Internal force of one element on its two nodes, in global axes (f_int: M a = P - f_int, as
// beam_force): fi, fj are [force, moment] of nodes i and j. ui, uj are the nodes' translations
// (their first three DOFs), qi, qj their total rotations. Fixed operation order: it is part of
// the result. Stages:
//  1. chord x, l and u_l (current_chord);
//  2. nodal triads T_n = Q_n R0^T (columns: node n's copy of the reference local axes, now);
//  3. corotated frame R_r (corotated_frame);
//  4. deformational rotations: Rbar_n = R_r Q_n R0^T = R_r T_n, theta_n = log(Rbar_n) (Battini
//     & Pacoste's R_r^T R_g R_0 in their column convention);
//  5. natural forces f_l = (N, m_i, m_j) of (u_l, theta_i, theta_j) (natural_forces);
//  6. f_g = B^T f_l, B the variation of (u_l, theta_i, theta_j) over [du_i, dw_i, du_j, dw_j]:
//     du_l = e1 . (du_j - du_i); dtheta_n = T_s^-1(theta_n) (w_n - w_r), with w_n = R_r dw_n
//     and w_r = R_r dw_r the corotated frame's spin in its own axes, w_r = G^T dp (local
//     components of dp):
//       w_r1 = eta (du_i3 - du_j3)/l + (eta_i2 w_i1 - eta_i1 w_i2 + eta_j2 w_j1 - eta_j1 w_j2)/2,
//       w_r2 = (du_i3 - du_j3)/l,  w_r3 = (du_j2 - du_i2)/l,
//     eta = q1/q2, eta_nk = (e_k . t_n2)/q2, q_k = e_k . q (Battini & Pacoste's G; the variation
//     of e3 = e1 x q / |e1 x q|). So with m~_n = T_s^-T(theta_n) m_n and s = m~_i + m~_j, in
//     local axes: node i's force (-N, s3/l, -(eta s1 + s2)/l), node j's its negative; node n's
//     moment m~_n - s1 (eta_n2, -eta_n1, 0)/2; then rotated to global by R_r^T.
//
// Stiffness-proportional damping (beta > 0, `rates` given): the natural forces of the
// deformation rates, beta f_l(d_l') with d_l' = B [v_i, w_i, v_j, w_j] (the rows of B above:
// du_l' = e1 . (v_j - v_i), dtheta_n' = T_s^-1(theta_n) (R_r w_n - w_r), T_s^-1(theta) =
// T_s^-T(-theta)), join the elastic ones before B^T. A rigid motion has d_l' = 0: the damping is
// objective, as the elastic force is. The returned natural forces are the elastic ones.
struct CorotationalRates {
  const double* vi = nullptr;  // node i's [v, w], m/s and rad/s, global (w spatial)
  const double* vj = nullptr;
  double beta = 0;  // s
};

inline CorotationalLocal corotational_force(const CorotationalBeam& b, const double* ui,
                                            const double* uj, const Quaternion& qi,
                                            const Quaternion& qj, double* fi, double* fj,
                                            const CorotationalRates& rates = {}) {
  const detail::Chord c = detail::current_chord(b, ui, uj);
  const Matrix3 Ti = detail::times_transpose(rotation_matrix(qi), b.rotation);
  const Matrix3 Tj = detail::times_transpose(rotation_matrix(qj), b.rotation);
  CorotationalLocal n;
  n.frame = detail::corotated_frame(c, Ti, Tj);
  n.length = c.length;
  n.stretch = c.stretch;
  const Matrix3 Ri = detail::times(n.frame, Ti);
  const Matrix3 Rj = detail::times(n.frame, Tj);
  n.theta_i = log_rotation(Ri);
  n.theta_j = log_rotation(Rj);
  detail::natural_forces(b.k, n);
  // q's local components from the rotated triads: q1 = e1 . q, q2 = e2 . q (= |e1 x q|).
  n.q2 = 0.5 * (Ri[4] + Rj[4]);
  const double inv_q2 = 1.0 / n.q2;
  const double eta = 0.5 * (Ri[1] + Rj[1]) * inv_q2;
  const double inv_l = c.inverse_length;
  Vector3 moment_i = n.moment_i, moment_j = n.moment_j;
  double axial = n.axial;
  if (rates.beta > 0) {
    const CorotationalLocal d =
        detail::natural_rates(b, n, Ri, Rj, inv_q2, eta, inv_l, rates.vi, rates.vj, rates.beta);
    axial += d.axial;
    for (std::size_t k = 0; k < 3; ++k)
      moment_i[k] += d.moment_i[k], moment_j[k] += d.moment_j[k];
  }

  const Vector3 mi = log_tangent_inverse_transpose(n.theta_i, moment_i);
  const Vector3 mj = log_tangent_inverse_transpose(n.theta_j, moment_j);
  const Vector3 s{mi[0] + mj[0], mi[1] + mj[1], mi[2] + mj[2]};
  const double shear_y = s[2] * inv_l, shear_z = (eta * s[0] + s[1]) * inv_l;
  const double half_s1 = 0.5 * s[0];
  const double local_force_i[3] = {-axial, shear_y, -shear_z};
  const double local_force_j[3] = {axial, -shear_y, shear_z};
  const double local_moment_i[3] = {mi[0] - half_s1 * (Ri[4] * inv_q2),
                                    mi[1] + half_s1 * (Ri[1] * inv_q2), mi[2]};
  const double local_moment_j[3] = {mj[0] - half_s1 * (Rj[4] * inv_q2),
                                    mj[1] + half_s1 * (Rj[1] * inv_q2), mj[2]};
  rotate_to_global(n.frame, local_force_i, fi), rotate_to_global(n.frame, local_moment_i, fi + 3);
  rotate_to_global(n.frame, local_force_j, fj), rotate_to_global(n.frame, local_moment_j, fj + 3);
  return n;
}

// A node's six DOFs, as an index step.
inline constexpr std::size_t kNodeDofs = static_cast<std::size_t>(kDofsPerNode);

// One corotational element as the step reads it.
struct CorotationalElement {
  CorotationalBeam beam;
  std::int32_t node_i = 0, node_j = 0;
  std::int32_t element = 0;  // its index in the model file (for the outputs)
  double limit = 0;  // N, Q_max of geometry.hpp: a tension N above it breaks the step's bound
};

// The stable step's bound (geometry.hpp) for a corotational element: the chord's rotation is the
// frame's, so Q = N+ alone. The moments' geometric terms, of order M / l^2 against the bending
// stiffness 12 E I / l^3 (a ratio of the deformational rotation over 12), are left out. And the
// frame's own range: it needs q off the chord, |e1 x q| = q2 > 0 (deformational rotations about
// local z under 90 degrees); below kCorotationalFooting (rotations near 60 degrees, far past small
// strains in any element) the element is counted as past its bound before its frame degenerates.
inline constexpr double kCorotationalFooting = 0.5;

inline bool corotational_over(const CorotationalElement& e, const CorotationalLocal& n) {
  return !(e.limit - (n.axial > 0 ? n.axial : 0.0) >= 0 && n.q2 >= kCorotationalFooting);
}

// f += the internal forces of `count` corotational elements at (u, q), in their order, with the
// stiffness-proportional damping of v when beta > 0; returns how many are past their bound.
// `rotations` by node.
inline std::size_t corotational_forces(const CorotationalElement* elements, std::size_t count,
                                       const double* u, const double* v,
                                       const Quaternion* rotations, double beta, double* f) {
  std::size_t over = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const CorotationalElement& e = elements[k];
    const auto i = static_cast<std::size_t>(e.node_i), j = static_cast<std::size_t>(e.node_j);
    const std::size_t di = kNodeDofs * i, dj = kNodeDofs * j;
    double fi[6], fj[6];
    const CorotationalRates rates{v + di, v + dj, beta};
    const CorotationalLocal n =
        corotational_force(e.beam, u + di, u + dj, rotations[i], rotations[j], fi, fj, rates);
    for (std::size_t c = 0; c < 6; ++c) {
      f[di + c] += fi[c];
      f[dj + c] += fj[c];
    }
    over += corotational_over(e, n) ? 1 : 0;
  }
  return over;
}

// Element e's end forces in its corotated frame (as beam_local_end_forces gives the linear
// element's in its local axes): [force, moment] at node i and at node j, the elastic part.
inline void corotational_local_end_forces(const CorotationalElement& e, const double* u,
                                          const Quaternion* rotations, double* out) {
  const auto i = static_cast<std::size_t>(e.node_i), j = static_cast<std::size_t>(e.node_j);
  double f[12];
  const CorotationalLocal n = corotational_force(e.beam, u + kNodeDofs * i, u + kNodeDofs * j,
                                                 rotations[i], rotations[j], f, f + 6);
  for (std::size_t k = 0; k < 4; ++k)
    rotate_to_local(n.frame, f + 3 * k, out + 3 * k);
}

// The element's strain energy: N u_l / 2 + the natural moments' (m_i . theta_i + m_j . theta_j)
// / 2, the linear element's in its corotated frame.
inline double corotational_energy(const CorotationalElement& e, const double* u,
                                  const Quaternion* rotations) {
  const auto i = static_cast<std::size_t>(e.node_i), j = static_cast<std::size_t>(e.node_j);
  double f[12];
  const CorotationalLocal n = corotational_force(e.beam, u + kNodeDofs * i, u + kNodeDofs * j,
                                                 rotations[i], rotations[j], f, f + 6);
  return 0.5 * (n.axial * n.stretch + dot(n.moment_i, n.theta_i) + dot(n.moment_j, n.theta_j));
}

// A node's rotation after a step: q_{n+1} = exp(dt omega) q_n, the increment on the left since
// omega is spatial (dQ = skew(omega) Q dt), renormalized against the drift of the product.
inline Quaternion advance_rotation(const Quaternion& q, const double* omega, double dt) {
  const Vector3 increment{dt * omega[0], dt * omega[1], dt * omega[2]};
  return renormalized(product(exp_rotation(increment), q));
}

}  // namespace ntn
