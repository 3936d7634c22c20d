// Regular 3D steel frames for the kernel benchmarks: a grid of bays in x and y on several storeys,
// every member meshed into several elements, base fixed, a floor mass at every floor joint.
// Sizes are compile-time (Grid -> ntn::Sizes); the spec is filled at run time into static storage.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <new>

#include "ntn/kernel.hpp"

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
  s.nodes = node_count(g);
  s.elements = element_count(g);
  s.inputs = kInputs;
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

// Fills `spec` with the frame of grid G. Node and element numbering go storey by storey (columns,
// then beams in x, then beams in y) so that neighbours in the mesh are near in memory.
template <Grid G>
void build_frame(ModelSpec<sizes_of(G)>& spec) {
  constexpr int kJ = joints_per_level(G);
  auto joint = [](int level, int ix, int iy) { return level * kJ + iy * (G.nx + 1) + ix; };
  int next_node = kJ * (G.storeys + 1);  // interior nodes follow the joints
  int next_element = 0;
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

  // One member from joint a to joint b meshed into `div` elements through new interior nodes.
  auto add_member = [&](int a, int b, int div, const Section& s, double rx, double ry, double rz) {
    const NodeSpec na = spec.nodes[static_cast<std::size_t>(a)];
    const NodeSpec nb = spec.nodes[static_cast<std::size_t>(b)];
    int prev = a;
    for (int k = 1; k <= div; ++k) {
      int cur = b;
      if (k < div) {
        cur = next_node++;
        const double t = static_cast<double>(k) / div;
        NodeSpec& n = spec.nodes[static_cast<std::size_t>(cur)];
        n.x = na.x + t * (nb.x - na.x), n.y = na.y + t * (nb.y - na.y);
        n.z = na.z + t * (nb.z - na.z);
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
        add_member(joint(level - 1, ix, iy), joint(level, ix, iy), G.col_div, kHEB300, 1, 0, 0);
      }
    }
    for (int iy = 0; iy <= G.ny; ++iy) {  // beams along x, web vertical
      for (int ix = 0; ix < G.nx; ++ix) {
        add_member(joint(level, ix, iy), joint(level, ix + 1, iy), G.beam_div, kIPE400, 0, 0, 1);
      }
    }
    for (int iy = 0; iy < G.ny; ++iy) {  // beams along y, web vertical
      for (int ix = 0; ix <= G.nx; ++ix) {
        add_member(joint(level, ix, iy), joint(level, ix, iy + 1), G.beam_div, kIPE400, 0, 0, 1);
      }
    }
  }

  // Ground acceleration channels in x and y, records in g.
  spec.inputs[0] = {.kind = InputKind::kGroundAcceleration, .dof = 0, .scale = 9.80665};
  spec.inputs[1] = {.kind = InputKind::kGroundAcceleration, .dof = 1, .scale = 9.80665};
  spec.settings.alpha = kAlpha;
  spec.settings.gravity = {0.0, 0.0, -9.80665};
  spec.settings.dt = kDtFraction * stable_time_step(view(spec)).dt_stable;
}

}  // namespace ntn::bench
