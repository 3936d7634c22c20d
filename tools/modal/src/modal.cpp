#include "ntn/modal/modal.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "eigensolve.hpp"
#include "ntn/hinge.hpp"
#include "ntn/modal/assembly.hpp"
#include "ntn/modal/constraints.hpp"
#include "ntn/model.hpp"

namespace ntn::modal {
namespace {

using detail::num;

using SpMat = Eigen::SparseMatrix<double>;
using Triplets = std::vector<Eigen::Triplet<double>>;

// A massless direction whose stiffness is below this fraction of the largest diagonal stiffness
// is a mechanism. Its exact stiffness is zero; the rounding of its basis (an SVD) leaves ~1e-16.
constexpr double kMechanismTolerance = 1e-10;
// Rank threshold of the SVD that finds massless combinations of a group's coordinates: T's
// entries are direction cosines and lever arms (m), so 1e-9 of the largest singular value (at
// least 1) separates rounding from a real motion (as the model compiler's mechanism check).
constexpr double kRankTolerance = 1e-9;

// K of the elements and of the hinges' springs, sum B^T diag(k) B (DESIGN §7), in global DOFs,
// plus the geometric stiffness K_g(N(u)) of the elements with second-order geometry at `about`
// when it is given (6 per node; geometry.hpp).
SpMat stiffness(const SpecView& spec, const std::vector<LinearHinge>& hinges, int& bad_element,
                const std::vector<double>* about = nullptr) {
  Triplets t;
  t.reserve(spec.elements.size() * 144);
  bad_element =
      for_each_element_stiffness(spec, [&t](int r, int c, double v) { t.emplace_back(r, c, v); });
  if (about != nullptr && bad_element < 0)
    for_each_geometric_stiffness(geometric_elements(spec), *about,
                                 [&t](int r, int c, double v) { t.emplace_back(r, c, v); });
  for (std::size_t h = 0; h < spec.hinges.size(); ++h) {
    HingeData hd;
    hd.node1 = spec.hinges[h].node1, hd.node2 = spec.hinges[h].node2;
    hd.frame = spec.hinges[h].frame;
    hd.eccentricity = spec.hinges[h].eccentricity;
    for (std::size_t k = 0; k < 6; ++k) {
      const double s = hinges[h].stiffness[k];
      if (((hinges[h].rigid >> k) & 1U) || !(s > 0)) continue;
      double b[12];
      hinge_direction(hd, k, b, b + 6);
      const int node[2] = {hd.node1, hd.node2};
      for (int i = 0; i < 12; ++i) {
        if (b[i] == 0.0 || node[i / 6] == kGround) continue;
        for (int j = 0; j < 12; ++j) {
          if (b[j] == 0.0 || node[j / 6] == kGround) continue;
          t.emplace_back(6 * node[i / 6] + i % 6, 6 * node[j / 6] + j % 6, s * b[i] * b[j]);
        }
      }
    }
  }
  const auto n = static_cast<Eigen::Index>(6 * spec.nodes.size());
  SpMat K(n, n);
  K.setFromTriplets(t.begin(), t.end());
  return K;
}

// The model's u_0 (NodeSpec::u0: the static preload and [initial] values), 6 per node: the
// state whose axial forces the geometric stiffness of modal analysis takes.
std::vector<double> initial_displacement(const SpecView& spec) {
  std::vector<double> u(kDofsPerNode * spec.nodes.size(), 0.0);
  for (std::size_t n = 0; n < spec.nodes.size(); ++n)
    for (std::size_t k = 0; k < kDofsPerNode; ++k)
      u[kDofsPerNode * n + k] = spec.nodes[n].u0[k];
  return u;
}

std::string dof_names(std::uint8_t bits) {
  static const char* const kName[6] = {"ux", "uy", "uz", "rx", "ry", "rz"};
  std::string s;
  for (int d = 0; d < 6; ++d) {
    if (!((bits >> d) & 1U)) continue;
    if (!s.empty()) s += ", ";
    s += kName[d];
  }
  return s;
}

// The stages' timer: each lap the seconds since the last.
class Laps {
 public:
  void lap(double& into) {
    const Clock::time_point now = Clock::now();
    into = std::chrono::duration<double>(now - mark_).count();
    mark_ = now;
  }

 private:
  using Clock = std::chrono::steady_clock;
  Clock::time_point mark_ = Clock::now();
};

// The problem in the constraints' coordinates q (u = T q): K and the lumped mass as the kernel
// assembles them, Kq = T^T K T and Mq = T^T M T.
struct Assembled {
  std::vector<double> mass;  // lumped, per global DOF
  SpMat Kq, Mq;
};

// q = S p + Z r: S spans the coordinates with mass (p^T p the kinetic energy), Z the massless.
struct MassReduction {
  SpMat S, Zs;
  int np = 0, nz = 0;
};

// The massless directions with stiffness, condensed statically: U_r (nz x count), their
// stiffness mu_r, and A_zp = Z^T Kq S, for the shapes' massless part.
struct Condensation {
  Eigen::MatrixXd Ur;
  Eigen::VectorXd mu_r;
  SpMat Azp;
};

// 1. Hinges linearized, supports and rigid directions as u = T q (constraints.hpp).
bool tie_constraints(const SpecView& spec, const ModalOptions& options, ModalResult& r,
                     HingeLinearization& lin, ConstraintMap& cm) {
  lin = linearize_hinges(spec, options.penalty_as_springs);
  if (!lin.error.empty()) {
    r.error = lin.error;
    return false;
  }
  r.notes = lin.notes;
  cm = build_constraints(spec, lin.hinges);
  if (!cm.error.empty()) {
    r.error = cm.error;
    return false;
  }
  r.trees = cm.trees;
  r.coordinates = static_cast<int>(cm.T.cols());
  return true;
}

// 2. K (elements, hinge springs) and the lumped mass as the kernel assembles them, in q.
bool assemble(const SpecView& spec, const HingeLinearization& lin, const ConstraintMap& cm,
              bool geometric, ModalResult& r, Assembled& a) {
  const int n = r.dofs;
  int bad_element = -1;
  const std::vector<double> u0 = initial_displacement(spec);
  const SpMat K = stiffness(spec, lin.hinges, bad_element, geometric ? &u0 : nullptr);
  if (bad_element >= 0) {
    r.error = "element " + std::to_string(bad_element) +
              " has a bad geometry or bad properties (zero length, orientation along the member, "
              "or a property not positive)";
    return false;
  }
  a.mass = lumped_mass(spec);
  const Eigen::Map<const Eigen::VectorXd> m(a.mass.data(), n);
  const SpMat& T = cm.T;
  a.Kq = SpMat(T.transpose() * K * T);
  a.Mq = SpMat(T.transpose() * m.asDiagonal() * T);
  return true;
}

// 3. Per group: Mq's block is SPD on the combinations that move mass (W), zero on the others
// (Z, massless). With W^T Mq W = L L^T, q = S p + Z r, S = W L^-T gives p^T p for the kinetic
// energy: the standard problem S^T Kq S y = omega^2 y (the M^-1/2 reduction, block by block).
bool reduce_mass(const ConstraintMap& cm, const Assembled& a, ModalResult& r, MassReduction& red) {
  const int n = r.dofs;
  const std::vector<double>& mass = a.mass;
  const SpMat& T = cm.T;
  const SpMat& Mq = a.Mq;
  Triplets s_t, z_t;
  int np = 0, nz = 0;
  std::vector<int> row_of(static_cast<std::size_t>(n), -1);  // workspace: DOF -> row of Tg
  for (const ConstraintGroup& g : cm.groups) {
    if (g.columns == 0) continue;
    const int b = g.first_column, c = g.columns;
    // The group's block of T on its nodes' DOFs, split into rows with and without mass.
    std::vector<int> heavy, light;
    for (int node : g.nodes) {
      for (int d = 0; d < 6; ++d) {
        const int j = 6 * node + d;
        (mass[static_cast<std::size_t>(j)] > 0 ? heavy : light).push_back(j);
      }
    }
    Eigen::MatrixXd Tg = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(heavy.size()), c);
    bool touches_light = false;
    for (std::size_t i = 0; i < heavy.size(); ++i)
      row_of[static_cast<std::size_t>(heavy[i])] = static_cast<int>(i);
    for (int k = 0; k < c; ++k) {
      for (SpMat::InnerIterator it(T, b + k); it; ++it) {
        const int row = row_of[static_cast<std::size_t>(it.row())];
        if (row >= 0) {
          Tg(row, k) = it.value();
        } else {
          touches_light = true;
        }
      }
    }
    for (int j : heavy)
      row_of[static_cast<std::size_t>(j)] = -1;
    Eigen::MatrixXd W, Z;
    if (!touches_light) {
      W = Eigen::MatrixXd::Identity(c, c);
    } else {
      const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Tg, Eigen::ComputeFullV);
      const Eigen::VectorXd& sv = svd.singularValues();
      const double tol = kRankTolerance * std::max(1.0, sv.size() > 0 ? sv(0) : 0.0);
      Eigen::Index rank = 0;
      while (rank < sv.size() && sv(rank) > tol)
        ++rank;
      W = svd.matrixV().leftCols(rank);
      Z = svd.matrixV().rightCols(c - rank);
    }
    const Eigen::MatrixXd Mg = Eigen::MatrixXd(Mq.block(b, b, c, c));
    const Eigen::LLT<Eigen::MatrixXd> llt(W.transpose() * Mg * W);
    if (llt.info() != Eigen::Success) {
      r.error = "the mass of the group of node " + std::to_string(g.nodes.front()) +
                " is not positive definite on its moving coordinates";
      return false;
    }
    // S_g = W L^-T: solve L X^T = W^T.
    const Eigen::MatrixXd Sg = llt.matrixL().solve(W.transpose()).transpose();
    for (Eigen::Index i = 0; i < Sg.rows(); ++i) {
      for (Eigen::Index k = 0; k < Sg.cols(); ++k) {
        if (Sg(i, k) != 0.0)
          s_t.emplace_back(b + static_cast<int>(i), np + static_cast<int>(k), Sg(i, k));
      }
    }
    np += static_cast<int>(Sg.cols());
    for (Eigen::Index i = 0; i < Z.rows(); ++i) {
      for (Eigen::Index k = 0; k < Z.cols(); ++k) {
        if (Z(i, k) != 0.0)
          z_t.emplace_back(b + static_cast<int>(i), nz + static_cast<int>(k), Z(i, k));
      }
    }
    nz += static_cast<int>(Z.cols());
  }
  red.S = SpMat(r.coordinates, np);
  red.Zs = SpMat(r.coordinates, nz);
  red.S.setFromTriplets(s_t.begin(), s_t.end());
  red.Zs.setFromTriplets(z_t.begin(), z_t.end());
  red.np = np, red.nz = nz;
  return true;
}

// The blocks of massless coordinates that the stiffness couples: the connected components of
// Azz's pattern (some empty).
std::vector<std::vector<int>> coupled_blocks(const SpMat& Azz, int nz) {
  std::vector<int> comp(static_cast<std::size_t>(nz));
  for (int i = 0; i < nz; ++i)
    comp[static_cast<std::size_t>(i)] = i;
  auto find = [&comp](int x) {
    while (comp[static_cast<std::size_t>(x)] != x)
      x = comp[static_cast<std::size_t>(x)] =
          comp[static_cast<std::size_t>(comp[static_cast<std::size_t>(x)])];
    return x;
  };
  for (Eigen::Index k = 0; k < Azz.outerSize(); ++k) {
    for (SpMat::InnerIterator it(Azz, k); it; ++it) {
      if (it.value() != 0.0)
        comp[static_cast<std::size_t>(find(static_cast<int>(it.row())))] =
            find(static_cast<int>(k));
    }
  }
  std::vector<std::vector<int>> blocks(static_cast<std::size_t>(nz));
  for (int i = 0; i < nz; ++i)
    blocks[static_cast<std::size_t>(find(i))].push_back(i);
  return blocks;
}

// What the condensation gathers over the blocks.
struct MasslessWork {
  std::vector<std::uint8_t> bits;   // per node: the DOFs its mechanisms move
  std::vector<Eigen::VectorXd> ur;  // massless directions with stiffness
  std::vector<double> mu;           // and their stiffness
  std::vector<int> pos;             // workspace: p row -> row of the block's A_pz
  Triplets corr;                    // -C C^T, the condensation's change of A
};

// One block of massless coordinates: its eigenvectors with stiffness are condensed (C gathers
// A_pz u mu^-1/2), those without are mechanisms (their DOFs marked).
void condense_block(const std::vector<int>& blk, const SpMat& Azz, const SpMat& Apz, double tol,
                    const SpMat& T, const SpMat& Zs, int nz, ModalResult& r, MasslessWork& w) {
  const auto nb = static_cast<Eigen::Index>(blk.size());
  Eigen::MatrixXd Ab(nb, nb);
  for (Eigen::Index i = 0; i < nb; ++i) {
    for (Eigen::Index j = 0; j < nb; ++j)
      Ab(i, j) = Azz.coeff(blk[static_cast<std::size_t>(i)], blk[static_cast<std::size_t>(j)]);
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(Ab);
  // The block's eigenvectors as full massless-coordinate vectors.
  auto full = [&](Eigen::Index e) {
    Eigen::VectorXd v = Eigen::VectorXd::Zero(nz);
    for (Eigen::Index i = 0; i < nb; ++i)
      v(blk[static_cast<std::size_t>(i)]) = es.eigenvectors()(i, e);
    return v;
  };
  std::vector<int> touched;  // p rows the block couples to
  for (int z : blk) {
    for (SpMat::InnerIterator it(Apz, z); it; ++it)
      touched.push_back(static_cast<int>(it.row()));
  }
  std::sort(touched.begin(), touched.end());
  touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
  for (std::size_t i = 0; i < touched.size(); ++i)
    w.pos[static_cast<std::size_t>(touched[i])] = static_cast<int>(i);
  Eigen::MatrixXd Apb = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(touched.size()), nb);
  for (Eigen::Index i = 0; i < nb; ++i) {
    for (SpMat::InnerIterator it(Apz, blk[static_cast<std::size_t>(i)]); it; ++it)
      Apb(w.pos[static_cast<std::size_t>(it.row())], i) = it.value();
  }
  Eigen::MatrixXd C(static_cast<Eigen::Index>(touched.size()), 0);
  for (Eigen::Index e = 0; e < nb; ++e) {
    const double lam = es.eigenvalues()(e);
    if (lam > tol) {  // stiffness: condensed; C gathers A_pz u mu^-1/2
      w.ur.push_back(full(e));
      w.mu.push_back(lam);
      C.conservativeResize(Eigen::NoChange, C.cols() + 1);
      C.col(C.cols() - 1) = Apb * es.eigenvectors().col(e) / std::sqrt(lam);
      continue;
    }
    ++r.mechanism_dofs;  // the DOFs it moves, in global axes (as the compiler reports)
    const Eigen::VectorXd u = T * (Zs * full(e));
    const double top = u.cwiseAbs().maxCoeff();
    for (Eigen::Index j = 0; j < u.size(); ++j) {
      if (std::abs(u(j)) > 1e-9 * top)
        w.bits[static_cast<std::size_t>(j / 6)] |= static_cast<std::uint8_t>(1U << (j % 6));
    }
  }
  if (C.cols() > 0) {  // A -= C C^T on the touched rows
    const Eigen::MatrixXd CC = C * C.transpose();
    for (Eigen::Index i = 0; i < CC.rows(); ++i) {
      for (Eigen::Index j = 0; j < CC.cols(); ++j)
        w.corr.emplace_back(touched[static_cast<std::size_t>(i)],
                            touched[static_cast<std::size_t>(j)], -CC(i, j));
    }
  }
  for (int t : touched)
    w.pos[static_cast<std::size_t>(t)] = -1;
}

// 4. Massless combinations: mechanisms (no stiffness) are removed; the others are condensed
// statically, A = A_pp - A_pr A_rr^-1 A_rp (exact for undamped modes: no inertia there). Done
// per block of massless coordinates that the stiffness couples, so that it stays local.
void condense_massless(const SpecView& spec, const SpMat& T, const SpMat& Kq,
                       const MassReduction& red, ModalResult& r, SpMat& A, Condensation& cond) {
  const int np = red.np, nz = red.nz;
  const SpMat& S = red.S;
  const SpMat& Zs = red.Zs;
  const SpMat Azz = SpMat(Zs.transpose() * Kq * Zs);
  cond.Azp = SpMat(Zs.transpose() * Kq * S);
  const SpMat Apz = SpMat(cond.Azp.transpose());
  const double kmax = Eigen::VectorXd(Kq.diagonal()).cwiseAbs().maxCoeff();
  const double tol = kMechanismTolerance * kmax;
  MasslessWork w;
  w.bits.assign(spec.nodes.size(), 0);
  w.pos.assign(static_cast<std::size_t>(np), -1);
  for (const std::vector<int>& blk : coupled_blocks(Azz, nz)) {
    if (blk.empty()) continue;
    condense_block(blk, Azz, Apz, tol, T, Zs, nz, r, w);
  }
  for (std::size_t i = 0; i < w.bits.size(); ++i) {
    if (w.bits[i] == 0) continue;
    r.mechanisms.push_back({static_cast<int>(i), w.bits[i]});
    r.notes.push_back("node " + std::to_string(i) + " has no effective mass and no stiffness in " +
                      dof_names(w.bits[i]) +
                      " (global axes): a mechanism, removed (the kernel holds it at zero)");
  }
  r.condensed = static_cast<int>(w.ur.size());
  if (w.ur.empty()) return;
  cond.Ur.resize(nz, static_cast<Eigen::Index>(w.ur.size()));
  cond.mu_r.resize(static_cast<Eigen::Index>(w.ur.size()));
  for (std::size_t k = 0; k < w.ur.size(); ++k) {
    cond.Ur.col(static_cast<Eigen::Index>(k)) = w.ur[k];
    cond.mu_r(static_cast<Eigen::Index>(k)) = w.mu[k];
  }
  SpMat D(np, np);
  D.setFromTriplets(w.corr.begin(), w.corr.end());
  A += D;
  r.notes.push_back(std::to_string(w.ur.size()) +
                    " massless coordinate(s) with stiffness condensed statically");
}

// 6. Shapes back in physical DOFs: q = S y + Z U_r r, r = -mu_r^-1 U_r^T A_zp y; u = T q. Then
// the periods, the Rayleigh damping ratios and each shape's sign.
void shapes_back(const SpecView& spec, const SpMat& T, const MassReduction& red,
                 const Condensation& cond, const Eigen::VectorXd& lambda, const Eigen::MatrixXd& Y,
                 int want, ModalResult& r) {
  const int n = r.dofs;
  Eigen::MatrixXd Q = red.S * Y;
  if (cond.Ur.size() > 0) {
    const Eigen::MatrixXd rr =
        -(cond.mu_r.cwiseInverse().asDiagonal() * (cond.Ur.transpose() * (cond.Azp * Y)));
    Q += red.Zs * (cond.Ur * rr);
  }
  r.shapes = T * Q;
  r.omega = lambda.cwiseMax(0.0).cwiseSqrt();
  r.frequency = r.omega / (2.0 * std::numbers::pi);
  r.period.resize(want);
  r.damping_ratio.resize(want);
  for (int i = 0; i < want; ++i) {
    const double w = r.omega(i);
    r.period(i) = w > 0 ? 2.0 * std::numbers::pi / w : std::numeric_limits<double>::infinity();
    // C = alpha M + beta K_el: the ratio alpha / (2 omega) + beta omega / 2 of an undamped mode
    // (exact for the elements' stiffness alone; hinge springs have their own dashpots, not here).
    r.damping_ratio(i) = w > 0 ? spec.settings.alpha / (2.0 * w) + spec.settings.beta * w / 2.0
                               : std::numeric_limits<double>::infinity();
    // Sign: the first entry (DOF order) of at least a tenth of the largest magnitude is positive.
    // (The largest entry itself is ambiguous in symmetric structures, where two entries of equal
    // magnitude and opposite sign differ by rounding only.)
    const double top = r.shapes.col(i).cwiseAbs().maxCoeff();
    for (Eigen::Index j = 0; j < n; ++j) {
      if (std::abs(r.shapes(j, i)) < 0.1 * top) continue;
      if (r.shapes(j, i) < 0) r.shapes.col(i) *= -1.0;
      break;
    }
  }
}

// 7. Participation Gamma = phi^T M iota_d and effective masses (phi^T M phi = 1). The sum over
// all modes is |S^T T^T M iota_d|^2; the total is the mass no support holds in d.
void participation(const SpecView& spec, const SpMat& T, const SpMat& S,
                   const std::vector<double>& mass, int want, ModalResult& r) {
  const int n = r.dofs;
  const Eigen::Map<const Eigen::VectorXd> m(mass.data(), n);
  r.participation.resize(want, 3);
  for (int d = 0; d < 3; ++d) {
    Eigen::VectorXd mi = Eigen::VectorXd::Zero(n);
    double total = 0;
    for (std::size_t node = 0; node < spec.nodes.size(); ++node) {
      const auto j = static_cast<Eigen::Index>(6 * node) + d;
      mi(j) = m(j);
      if (!((spec.nodes[node].fixed >> d) & 1U)) total += m(j);
    }
    r.participation.col(d) = r.shapes.transpose() * mi;
    r.total_mass[static_cast<std::size_t>(d)] = total;
    r.reachable_mass[static_cast<std::size_t>(d)] =
        (S.transpose() * (T.transpose() * mi)).squaredNorm();
  }
  r.effective_mass = r.participation.cwiseAbs2();
  for (int d = 0; d < 3; ++d) {
    const double t = r.total_mass[static_cast<std::size_t>(d)];
    const double reach = r.reachable_mass[static_cast<std::size_t>(d)];
    if (t > 0 && std::abs(reach - t) > 1e-9 * t) {
      r.notes.push_back(std::string("direction ") + "xyz"[d] + ": " + num(t - reach) +
                        " kg of the unsupported mass cannot translate rigidly (tied to supports "
                        "or the ground through hinges): the effective masses add up to " +
                        num(reach) + " kg");
    }
  }
}

}  // namespace

namespace {

// K u = P in the coordinates q of the constraints (u = T q), coordinates without stiffness left
// at zero (mechanisms the kernel holds): false and the reason when a load acts on one
// (`check_mechanisms`) or K is not positive definite on the others (`singular`).
bool solve_constrained(const SpMat& K, const SpMat& T, const Eigen::VectorXd& load,
                       bool check_mechanisms, const std::string& singular, Eigen::VectorXd& u,
                       std::string& error) {
  const SpMat Kq = SpMat(T.transpose() * K * T);
  const Eigen::VectorXd Pq = T.transpose() * load;
  const Eigen::VectorXd diag = Kq.diagonal();
  const double kmax = diag.cwiseAbs().maxCoeff();
  const double pmax = Pq.cwiseAbs().maxCoeff();
  std::vector<int> keep_of(static_cast<std::size_t>(Kq.cols()), -1);
  int kept = 0;
  for (Eigen::Index c = 0; c < Kq.cols(); ++c) {
    if (diag(c) > kMechanismTolerance * kmax) {
      keep_of[static_cast<std::size_t>(c)] = kept++;
    } else if (check_mechanisms && std::abs(Pq(c)) > 1e-12 * pmax) {
      error =
          "a load acts on a DOF that nothing holds (a mechanism): the structure cannot "
          "carry it statically";
      return false;
    }
  }
  Triplets t;
  for (Eigen::Index c = 0; c < Kq.outerSize(); ++c) {
    for (SpMat::InnerIterator it(Kq, c); it; ++it) {
      const int i = keep_of[static_cast<std::size_t>(it.row())];
      const int j = keep_of[static_cast<std::size_t>(it.col())];
      if (i >= 0 && j >= 0) t.emplace_back(i, j, it.value());
    }
  }
  SpMat Kr(kept, kept);
  Kr.setFromTriplets(t.begin(), t.end());
  Eigen::VectorXd Pr(kept);
  for (Eigen::Index c = 0; c < Kq.cols(); ++c) {
    const int i = keep_of[static_cast<std::size_t>(c)];
    if (i >= 0) Pr(i) = Pq(c);
  }
  Eigen::SimplicialLDLT<SpMat, Eigen::Lower, Eigen::AMDOrdering<int>> ldlt(Kr);
  bool ok = ldlt.info() == Eigen::Success;
  if (ok && kept > 0) {
    // Positive definite to working precision; a pivot near zero is a rigid-body motion.
    const Eigen::VectorXd d = ldlt.vectorD();
    ok = d.minCoeff() > 1e-13 * d.cwiseAbs().maxCoeff();
  }
  if (!ok) {
    error = singular;
    return false;
  }
  const Eigen::VectorXd qr = kept > 0 ? Eigen::VectorXd(ldlt.solve(Pr)) : Eigen::VectorXd(Pr);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(Kq.cols());
  for (Eigen::Index c = 0; c < Kq.cols(); ++c) {
    const int i = keep_of[static_cast<std::size_t>(c)];
    if (i >= 0) q(c) = qr(i);
  }
  u = T * q;
  return true;
}

// The internal force at u of a model whose elements may have second-order geometry: K u plus
// the step's own second-order forces (ntn::geometric_forces).
Eigen::VectorXd internal_force(const SpMat& K, const std::vector<GeometricElement>& geometric,
                               const Eigen::VectorXd& u) {
  Eigen::VectorXd f = K * u;
  geometric_forces(geometric.data(), geometric.size(), u.data(), f.data());
  return f;
}

constexpr int kPreloadIterations = 50;
constexpr double kPreloadTolerance = 1e-12;  // |T^T (F(u) - P)| / |T^T P|

}  // namespace

// With second-order geometry the equilibrium F(u) = P is nonlinear: Newton's method with the
// tangent K + K_g(N(u)) (geometry.hpp) from u = 0, to kPreloadTolerance.
StaticResult static_solution(const SpecView& spec, std::span<const double> load) {
  StaticResult r;
  const auto n = static_cast<Eigen::Index>(kDofsPerNode * spec.nodes.size());
  if (static_cast<Eigen::Index>(load.size()) != n) {
    r.error = "the load vector has " + std::to_string(load.size()) + " entries, the model " +
              std::to_string(n) + " DOFs";
    return r;
  }
  const HingeLinearization lin =
      linearize_hinges(spec, spec.settings.hinge_method == HingeMethod::kPenalty);
  if (!lin.error.empty()) {
    r.error = lin.error;
    return r;
  }
  for (const std::string& note : lin.notes) {
    // At rest the dashpots carry nothing: that note is about modes, not statics.
    if (note.rfind("hinge dashpots", 0) != 0) r.notes.push_back(note);
  }
  const ConstraintMap cm = build_constraints(spec, lin.hinges);
  if (!cm.error.empty()) {
    r.error = cm.error;
    return r;
  }
  int bad_element = -1;
  const SpMat K = stiffness(spec, lin.hinges, bad_element);
  if (bad_element >= 0) {
    r.error = "element " + std::to_string(bad_element) + " has a bad geometry or bad properties";
    return r;
  }
  const Eigen::VectorXd P = Eigen::Map<const Eigen::VectorXd>(load.data(), n);
  const double pn = (cm.T.transpose() * P).norm();
  const std::vector<GeometricElement> geometric = geometric_elements(spec);
  Eigen::VectorXd u;
  if (!solve_constrained(K, cm.T, P, true,
                         "the stiffness is singular: the structure (supports, hinges) can move as "
                         "a rigid body or has a mechanism that the load would move",
                         u, r.error))
    return r;
  // The tangent K + K_g(N(u)), and what it means when it is not positive definite.
  const auto tangent = [&](const Eigen::VectorXd& at) {
    const std::vector<double> about(at.data(), at.data() + at.size());
    int bad = -1;
    return stiffness(spec, lin.hinges, bad, &about);
  };
  const std::string buckles =
      "the tangent stiffness K + K_g under the preload's axial forces is not positive definite: "
      "the structure buckles (P-Delta) under gravity and the constant loads";
  Eigen::VectorXd residual = P - internal_force(K, geometric, u);
  for (int it = 0; !geometric.empty() && it < kPreloadIterations; ++it) {
    if (!(pn > 0) || (cm.T.transpose() * residual).norm() <= kPreloadTolerance * pn) break;
    Eigen::VectorXd du;
    if (!solve_constrained(tangent(u), cm.T, residual, false, buckles, du, r.error)) return r;
    u += du;
    residual = P - internal_force(K, geometric, u);
  }
  r.relative_residual = pn > 0 ? (cm.T.transpose() * residual).norm() / pn : 0.0;
  if (!geometric.empty() && !(r.relative_residual <= kPreloadTolerance)) {
    r.error = "no static equilibrium with P-Delta after " + std::to_string(kPreloadIterations) +
              " Newton iterations (relative residual " + num(r.relative_residual) +
              "): the preload is at or past the structure's buckling load";
    return r;
  }
  // A stable equilibrium: the tangent positive definite there (a straight column above P_cr is an
  // equilibrium too).
  Eigen::VectorXd probe;
  if (!geometric.empty() && !solve_constrained(tangent(u), cm.T, P, false, buckles, probe, r.error))
    return r;
  r.u.assign(u.data(), u.data() + u.size());
  return r;
}

double ModalResult::shape(int mode, int node, int dof) const {
  return shapes(kDofsPerNode * node + dof, mode);
}

double ModalResult::mass_fraction(int mode, int d) const {
  const double t = total_mass[static_cast<std::size_t>(d)];
  return t > 0 ? effective_mass(mode, d) / t : 0.0;
}

double ModalResult::cumulative_fraction(int mode, int d) const {
  double s = 0;
  for (int i = 0; i <= mode; ++i)
    s += mass_fraction(i, d);
  return s;
}

ModalResult modal_analysis(const SpecView& spec, const ModalOptions& options) {
  ModalResult r;
  Laps laps;
  const int n = 6 * static_cast<int>(spec.nodes.size());
  r.dofs = n;
  if (spec.nodes.empty()) {
    r.error = "the model has no nodes";
    return r;
  }
  HingeLinearization lin;
  ConstraintMap cm;
  if (!tie_constraints(spec, options, r, lin, cm)) return r;
  Assembled a;
  if (!assemble(spec, lin, cm, options.geometric, r, a)) return r;
  laps.lap(r.seconds.assembly);

  MassReduction red;
  if (!reduce_mass(cm, a, r, red)) return r;
  SpMat A = SpMat(red.S.transpose() * a.Kq * red.S);
  Condensation cond;
  if (red.nz > 0) condense_massless(spec, cm.T, a.Kq, red, r, A, cond);
  const int np = red.np;
  r.reduced = np;
  laps.lap(r.seconds.reduction);
  if (np == 0) {
    r.error = "no DOF with mass is free to move";
    return r;
  }

  // 5. The standard symmetric problem A y = omega^2 y: the lowest `modes`.
  const bool all = options.modes <= 0 || options.modes >= np;
  const int want = all ? np : options.modes;
  bool dense = options.solver == Solver::kDense ||
               (options.solver == Solver::kAuto && np <= options.dense_limit) || all;
  if (options.solver == Solver::kSparse && all) {
    r.notes.push_back("all modes asked for: solved dense");
  }
  Eigen::VectorXd lambda;
  Eigen::MatrixXd Y;
  if (!(dense ? detail::solve_dense(A, want, r, lambda, Y)
              : detail::solve_sparse(A, np, want, options, r, lambda, Y)))
    return r;
  laps.lap(r.seconds.eigensolver);

  shapes_back(spec, cm.T, red, cond, lambda, Y, want, r);
  participation(spec, cm.T, red.S, a.mass, want, r);
  laps.lap(r.seconds.results);
  return r;
}

Eigen::MatrixXd shapes_at(const ModalResult& r, std::span<const Channel> channels) {
  Eigen::MatrixXd out(static_cast<Eigen::Index>(channels.size()), r.modes());
  for (std::size_t c = 0; c < channels.size(); ++c)
    out.row(static_cast<Eigen::Index>(c)) =
        r.shapes.row(kDofsPerNode * channels[c].node + channels[c].dof);
  return out;
}

double mac(const Eigen::Ref<const Eigen::VectorXd>& a, const Eigen::Ref<const Eigen::VectorXd>& b) {
  const double aa = a.squaredNorm(), bb = b.squaredNorm();
  if (!(aa > 0) || !(bb > 0)) return 0.0;
  const double ab = a.dot(b);
  return ab * ab / (aa * bb);
}

double mac(const Eigen::Ref<const Eigen::VectorXcd>& a,
           const Eigen::Ref<const Eigen::VectorXcd>& b) {
  const double aa = a.squaredNorm(), bb = b.squaredNorm();
  if (!(aa > 0) || !(bb > 0)) return 0.0;
  return std::norm(a.dot(b)) / (aa * bb);  // dot conjugates a: a^H b
}

Eigen::MatrixXd mac_matrix(const Eigen::Ref<const Eigen::MatrixXd>& A,
                           const Eigen::Ref<const Eigen::MatrixXd>& B) {
  Eigen::MatrixXd out(A.cols(), B.cols());
  for (Eigen::Index i = 0; i < A.cols(); ++i) {
    for (Eigen::Index j = 0; j < B.cols(); ++j)
      out(i, j) = mac(A.col(i), B.col(j));
  }
  return out;
}

}  // namespace ntn::modal
