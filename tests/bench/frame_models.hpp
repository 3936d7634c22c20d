// Regular 3D steel frames for the kernel benchmarks: a grid of bays in x and y on several storeys,
// every member meshed into several elements, base fixed, a floor mass at every floor joint.
// Beams meet the columns either in a merged node (fully fixed) or through an NTN hinge at each
// beam end (pinned, or a mix of hinge kinds). Sizes are compile-time (Grid, Joints ->
// ntn::Sizes); the spec is filled at run time into static storage.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <new>
#include <vector>

#include "ntn/kernel.hpp"
#include "ntn/modal/assembly.hpp"

namespace ntn::bench {

// nx x ny bays, `storeys` storeys; columns meshed into col_div elements, beams into beam_div.
struct Grid {
  int nx = 1, ny = 1, storeys = 1;
  int col_div = 1, beam_div = 1;
};

constexpr int joints_per_level(Grid g) {
  return (g.nx + 1) * (g.ny + 1);
}
constexpr int columns(Grid g) {
  return joints_per_level(g) * g.storeys;
}
constexpr int beams(Grid g) {
  return (g.nx * (g.ny + 1) + (g.nx + 1) * g.ny) * g.storeys;
}
constexpr int element_count(Grid g) {
  return columns(g) * g.col_div + beams(g) * g.beam_div;
}
constexpr int node_count(Grid g) {
  return joints_per_level(g) * (g.storeys + 1) + columns(g) * (g.col_div - 1) +
         beams(g) * (g.beam_div - 1);
}

inline constexpr int kInputs = 2;  // ground acceleration in x and in y (in g)

constexpr Sizes sizes_of(Grid g) {
  Sizes s;
  s.nodes = static_cast<std::size_t>(node_count(g));
  s.elements = static_cast<std::size_t>(element_count(g));
  s.inputs = kInputs;
  return s;
}

// How the beams meet the columns.
enum class Joints : std::uint8_t {
  kMerged,     // beam ends share the column's node: fully fixed connections, no hinges
  kPinned,     // each beam end has its own node and an NTN hinge to the column's node, in the
               // beam's local axes: rigid in ux, uy, uz, rx (torsion), free in ry, rz
  kMixed,      // as kPinned, but ry is a `curve` with a +-0.1 mrad gap between rigid stops and rz a
               // `linear` spring with a dashpot: every hinge kind in one model
  kSemiRigid,  // as kPinned, but ry and rz are `linear` rotational springs kSemiRigidSpring
  kPlastic,    // as kSemiRigid, but ry and rz are `plastic` (same k, yield kPlasticYield): the
               // beam ends yield under the benchmark load
  kRigidPlastic,  // as kPinned, but ry and rz are `rigid_plastic` (yield kPlasticYield): rigid
                  // until they yield, then sliding
};

constexpr int hinge_count(Grid g, Joints j) {
  return j == Joints::kMerged ? 0 : 2 * beams(g);
}

constexpr Sizes sizes_of(Grid g, Joints j) {
  Sizes s = sizes_of(g);
  s.hinges = static_cast<std::size_t>(hinge_count(g, j));
  s.nodes += s.hinges;  // one node of its own per hinged beam end
  if (j == Joints::kMixed) s.curves = 1, s.curve_points = 4;
  if (j == Joints::kPlastic || j == Joints::kRigidPlastic)
    s.hystereses = 2 * s.hinges;  // ry and rz of every hinge
  return s;
}

// Geometry and loads of every benchmark frame.
inline constexpr double kBay = 6.0;          // m, bay width in x and y
inline constexpr double kStorey = 3.5;       // m, storey height
inline constexpr double kFloorMass = 600.0;  // kg/m^2: slab, finishes and part of the live load
inline constexpr double kAlpha = 0.25;       // 1/s, mass-proportional damping (2 % near 1 Hz)
inline constexpr double kDtFraction = 0.9;   // dt = 0.9 x stable step

// Steel S355: E, G, rho.
inline constexpr double kE = 210e9, kG = 81e9, kRho = 7850.0;

struct Section {
  double A, Iy, Iz, J;  // m^2, m^4 (strong axis), m^4 (weak axis), m^4 (torsion)
};
inline constexpr Section kHEB300{149.1e-4, 25170e-8, 8563e-8, 185.0e-8};  // columns
inline constexpr Section kIPE400{84.46e-4, 23130e-8, 1318e-8, 51.08e-8};  // beams

// Joints::kMixed. ry (strong-axis bending of the beam): free within +-kGap, then rigid stops
// (curve segments of slope kStopSlope >= the limit stiffness). Self-weight alone turns a pinned
// IPE 400 end by q l^3 / (24 E I) = 1.2e-4 rad, so the stops engage. rz (weak axis): a rotational
// spring and dashpot, soft enough not to lower the stable step.
inline constexpr double kGap = 1e-4;                // rad
inline constexpr double kStopSlope = 1e10;          // N m/rad
inline constexpr double kLimitRotStiffness = 1e10;  // N m/rad, curve slopes >= this are rigid
inline constexpr double kMixedSpring = 1e6;         // N m/rad
inline constexpr double kMixedDashpot = 1e3;        // N m s/rad

// Joints::kSemiRigid and kPlastic: ry and rz rotational springs of about 0.6 x the IPE 400's
// 4 E I / l (3.2e7 N m/rad), soft enough not to lower the stable step. The plastic ones yield at
// 30 kN m (hardening 2 %), below the ~60 kN m that gravity alone puts on a semi-rigid beam end
// (q l^2 / 12 with q ~ 35 kN/m, l = 6 m, shared with the span): they yield from the first steps.
inline constexpr double kSemiRigidSpring = 2e7;  // N m/rad
inline constexpr double kPlasticYield = 3e4;     // N m
inline constexpr double kPlasticHardening = 0.02;

// Placement of T into static storage (no heap), value-initialized at first use. Large models do
// not fit the stack and should not sit in the executable's data section as constant initializers.
// `Tag` gives a second instance of the same type.
template <class T, int Tag = 0>
T& static_instance() {
  alignas(T) static std::byte storage[sizeof(T)];
  static T* const p = ::new (static_cast<void*>(storage)) T();
  return *p;
}

namespace detail {

inline ElementSpec element(int i, int j, const Section& s, double rx, double ry, double rz,
                           int member) {
  ElementSpec e;
  e.node_i = i, e.node_j = j;
  e.E = kE, e.G = kG, e.rho = kRho;
  e.A = s.A, e.Iy = s.Iy, e.Iz = s.Iz, e.J = s.J;
  e.ref_x = rx, e.ref_y = ry, e.ref_z = rz;
  e.member = member;
  return e;
}

}  // namespace detail

// dt_stable of a spec with its hinges' springs (DESIGN §6), from the lumped masses.
inline StableStepReport stable_step_with_hinges(const SpecView& v) {
  return stable_time_step(v, modal::lumped_mass(v));
}

// Fills `spec` with the frame of grid G. Node and element numbering go storey by storey (columns,
// then beams in x, then beams in y) so that neighbours in the mesh are near in memory. A hinged
// beam end's own node is numbered with that beam's interior nodes (start, interior, end), and its
// hinge (node 1 = beam end, node 2 = column joint) follows the order of the beams.
template <Grid G, Joints J = Joints::kMerged>
void build_frame(ModelSpec<sizes_of(G, J)>& spec) {
  constexpr int kJ = joints_per_level(G);
  constexpr bool kHinged = J != Joints::kMerged;
  auto joint = [](int level, int ix, int iy) { return level * kJ + iy * (G.nx + 1) + ix; };
  int next_node = kJ * (G.storeys + 1);  // interior nodes follow the joints
  int next_element = 0;
  int next_hinge = 0;
  int member = 0;

  for (int level = 0; level <= G.storeys; ++level) {
    for (int iy = 0; iy <= G.ny; ++iy) {
      for (int ix = 0; ix <= G.nx; ++ix) {
        NodeSpec& n = spec.nodes[static_cast<std::size_t>(joint(level, ix, iy))];
        n.x = kBay * ix, n.y = kBay * iy, n.z = kStorey * level;
        if (level == 0) {
          n.fixed = 0x3F;  // base fixed in all six DOFs
        } else {
          // Tributary floor area: half a bay on each side that has a bay.
          const double wx = kBay * (((ix > 0) ? 0.5 : 0.0) + ((ix < G.nx) ? 0.5 : 0.0));
          const double wy = kBay * (((iy > 0) ? 0.5 : 0.0) + ((iy < G.ny) ? 0.5 : 0.0));
          const double m = kFloorMass * wx * wy;
          n.added = {m, m, m, 0, 0, 0};
        }
      }
    }
  }

  // A node of its own at joint `at` for a hinged beam end, and its hinge to the joint in the
  // beam's local axes.
  auto hinge_end = [&](int at, const std::array<double, 9>& frame) {
    const int end = next_node++;
    spec.nodes[static_cast<std::size_t>(end)] = NodeSpec{};
    NodeSpec& n = spec.nodes[static_cast<std::size_t>(end)];
    const NodeSpec& j = spec.nodes[static_cast<std::size_t>(at)];
    n.x = j.x, n.y = j.y, n.z = j.z;
    if constexpr (kHinged) {
      HingeSpec& h = spec.hinges[static_cast<std::size_t>(next_hinge++)];
      h.node1 = end, h.node2 = at;
      h.frame = frame;
      h.behaviour = {HingeBehaviour::kRigid, HingeBehaviour::kRigid, HingeBehaviour::kRigid,
                     HingeBehaviour::kRigid, HingeBehaviour::kFree,  HingeBehaviour::kFree};
      if constexpr (J == Joints::kMixed) {
        h.behaviour[kRy] = HingeBehaviour::kCurve, h.curve[kRy] = 0;
        h.behaviour[kRz] = HingeBehaviour::kLinear;
        h.stiffness[kRz] = kMixedSpring, h.dashpot[kRz] = kMixedDashpot;
      }
      if constexpr (J == Joints::kRigidPlastic) {
        const int slot = 2 * (next_hinge - 1);
        h.behaviour[kRy] = h.behaviour[kRz] = HingeBehaviour::kRigidPlastic;
        h.hysteresis[kRy] = slot, h.hysteresis[kRz] = slot + 1;
        for (int k = 0; k < 2; ++k) {
          spec.hystereses[static_cast<std::size_t>(slot + k)] = {.yield_pos = kPlasticYield,
                                                                 .yield_neg = kPlasticYield};
        }
      }
      if constexpr (J == Joints::kSemiRigid || J == Joints::kPlastic) {
        constexpr HingeBehaviour kB =
            J == Joints::kPlastic ? HingeBehaviour::kPlastic : HingeBehaviour::kLinear;
        h.behaviour[kRy] = h.behaviour[kRz] = kB;
        h.stiffness[kRy] = h.stiffness[kRz] = kSemiRigidSpring;
        if constexpr (J == Joints::kPlastic) {
          const int slot = 2 * (next_hinge - 1);
          h.hysteresis[kRy] = slot, h.hysteresis[kRz] = slot + 1;
          for (int k = 0; k < 2; ++k) {
            spec.hystereses[static_cast<std::size_t>(slot + k)] = {.yield_pos = kPlasticYield,
                                                                   .yield_neg = kPlasticYield,
                                                                   .hardening = kPlasticHardening};
          }
        }
      }
    }
    return end;
  };

  // One member from joint a to joint b meshed into `div` elements through new interior nodes;
  // with `pinned`, through a hinged node of its own at each end.
  auto add_member = [&](int a, int b, int div, const Section& s, double rx, double ry, double rz,
                        bool pinned) {
    const NodeSpec na = spec.nodes[static_cast<std::size_t>(a)];
    const NodeSpec nb = spec.nodes[static_cast<std::size_t>(b)];
    const std::array<double, 9> frame =
        beam_geometry(na, nb, detail::element(a, b, s, rx, ry, rz, member)).rotation;
    int prev = pinned ? hinge_end(a, frame) : a;
    for (int k = 1; k <= div; ++k) {
      int cur = b;
      if (k < div) {
        cur = next_node++;
        const double t = static_cast<double>(k) / div;
        NodeSpec& n = spec.nodes[static_cast<std::size_t>(cur)];
        n.x = na.x + t * (nb.x - na.x), n.y = na.y + t * (nb.y - na.y);
        n.z = na.z + t * (nb.z - na.z);
      } else if (pinned) {
        cur = hinge_end(b, frame);
      }
      spec.elements[static_cast<std::size_t>(next_element++)] =
          detail::element(prev, cur, s, rx, ry, rz, member);
      prev = cur;
    }
    ++member;
  };

  for (int level = 1; level <= G.storeys; ++level) {
    for (int iy = 0; iy <= G.ny; ++iy) {  // columns: strong axis (Iy) bends in the x-z plane
      for (int ix = 0; ix <= G.nx; ++ix) {
        add_member(joint(level - 1, ix, iy), joint(level, ix, iy), G.col_div, kHEB300, 1, 0, 0,
                   false);
      }
    }
    for (int iy = 0; iy <= G.ny; ++iy) {  // beams along x, web vertical
      for (int ix = 0; ix < G.nx; ++ix) {
        add_member(joint(level, ix, iy), joint(level, ix + 1, iy), G.beam_div, kIPE400, 0, 0, 1,
                   kHinged);
      }
    }
    for (int iy = 0; iy < G.ny; ++iy) {  // beams along y, web vertical
      for (int ix = 0; ix <= G.nx; ++ix) {
        add_member(joint(level, ix, iy), joint(level, ix, iy + 1), G.beam_div, kIPE400, 0, 0, 1,
                   kHinged);
      }
    }
  }

  if constexpr (J == Joints::kMixed) {
    spec.curves[0] = {.first = 0, .count = 4};
    spec.curve_points = {CurvePoint{-2 * kGap, -kStopSlope * kGap}, CurvePoint{-kGap, 0.0},
                         CurvePoint{kGap, 0.0}, CurvePoint{2 * kGap, kStopSlope * kGap}};
    spec.settings.limit_rotational_stiffness = kLimitRotStiffness;
  }

  // Ground acceleration channels in x and y, records in g.
  spec.inputs[0] = {.kind = InputKind::kGroundAcceleration, .dof = 0, .scale = 9.80665};
  spec.inputs[1] = {.kind = InputKind::kGroundAcceleration, .dof = 1, .scale = 9.80665};
  spec.settings.alpha = kAlpha;
  spec.settings.gravity = {0.0, 0.0, -9.80665};
  if constexpr (kHinged) {
    spec.settings.dt = kDtFraction * stable_step_with_hinges(view(spec)).dt_stable;
  } else {
    spec.settings.dt = kDtFraction * stable_time_step(view(spec)).dt_stable;
  }
}

}  // namespace ntn::bench
