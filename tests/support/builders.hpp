// Model builders for tests: materials, sections and frames meshed into elements, written into a
// caller-owned (usually static) ntn::ModelSpec. No heap, no exceptions: usable from every test
// target, including the -fno-exceptions one.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>

#include "ntn/model_spec.hpp"

namespace ntn_test {

using Vec3 = std::array<double, 3>;

inline constexpr std::uint8_t kFixedAll = 0x3f;           // all six DOFs held
inline constexpr std::uint8_t kFixedTranslations = 0x07;  // ux, uy, uz held

struct Material {
  double E = 0;    // Pa
  double G = 0;    // Pa
  double rho = 0;  // kg/m^3
};

// Structural steel: E = 210 GPa, nu = 0.3, G = E / (2 (1 + nu)).
inline constexpr Material kSteel{210e9, 210e9 / 2.6, 7850.0};

struct Section {
  double A = 0, Iy = 0, Iz = 0, J = 0;        // m^2, m^4, m^4, m^4
  double shear_area_y = 0, shear_area_z = 0;  // m^2; 0 = Euler-Bernoulli
};

// Solid rectangle, width b along local y and depth h along local z: Iy = b h^3 / 12 (bending in
// the local x-z plane), Iz = h b^3 / 12. J by the usual series approximation for a rectangle
// (Roark): J = a c^3 (1/3 - 0.21 (c/a)(1 - (c/a)^4 / 12)), a >= c the long and short sides.
// With `timoshenko`, shear areas kappa A with kappa = 5/6.
constexpr Section rectangle(double b, double h, bool timoshenko = false) {
  const double a = b > h ? b : h, c = b > h ? h : b;
  const double r = c / a;
  Section s;
  s.A = b * h;
  s.Iy = b * h * h * h / 12.0;
  s.Iz = h * b * b * b / 12.0;
  s.J = a * c * c * c * (1.0 / 3.0 - 0.21 * r * (1.0 - r * r * r * r / 12.0));
  if (timoshenko) s.shear_area_y = s.shear_area_z = 5.0 / 6.0 * s.A;
  return s;
}

// Solid circle of radius r: Iy = Iz = pi r^4 / 4, J = pi r^4 / 2.
constexpr Section circle(double r) {
  constexpr double kPi = 3.14159265358979323846;
  Section s;
  s.A = kPi * r * r;
  s.Iy = s.Iz = kPi * r * r * r * r / 4.0;
  s.J = 2.0 * s.Iy;
  return s;
}

inline ntn::ElementSpec element(int i, int j, const Material& m, const Section& s,
                                const Vec3& ref) {
  ntn::ElementSpec e;
  e.node_i = i, e.node_j = j;
  e.E = m.E, e.G = m.G, e.rho = m.rho;
  e.A = s.A, e.Iy = s.Iy, e.Iz = s.Iz, e.J = s.J;
  e.shear_area_y = s.shear_area_y, e.shear_area_z = s.shear_area_z;
  e.ref_x = ref[0], e.ref_y = ref[1], e.ref_z = ref[2];
  return e;
}

// Fills a ModelSpec node by node and member by member. Members are meshed into equal elements;
// the intermediate nodes are numbered in order from `a` to `b`. `complete()` says whether every
// node and element slot of the spec was used (tests assert it).
template <ntn::Sizes S>
class FrameBuilder {
 public:
  explicit FrameBuilder(ntn::ModelSpec<S>& spec) : spec_(spec) {}

  int add_node(const Vec3& p, std::uint8_t fixed = 0) {
    ntn::NodeSpec& n = spec_.nodes[static_cast<std::size_t>(nodes_)];
    n.x = p[0], n.y = p[1], n.z = p[2];
    n.fixed = fixed;
    n.added = {};
    return nodes_++;
  }

  // Member from existing node a to existing node b in `divisions` elements (divisions - 1 new
  // nodes). Returns the index of its first element.
  int add_member(int a, int b, int divisions, const Material& m, const Section& s,
                 const Vec3& ref) {
    const ntn::NodeSpec na = spec_.nodes[static_cast<std::size_t>(a)];
    const ntn::NodeSpec nb = spec_.nodes[static_cast<std::size_t>(b)];
    const int first = elements_;
    int prev = a;
    for (int k = 1; k <= divisions; ++k) {
      int next = b;
      if (k < divisions) {
        const double t = static_cast<double>(k) / static_cast<double>(divisions);
        next = add_node(
            {na.x + t * (nb.x - na.x), na.y + t * (nb.y - na.y), na.z + t * (nb.z - na.z)});
      }
      ntn::ElementSpec e = element(prev, next, m, s, ref);
      e.member = members_;
      spec_.elements[static_cast<std::size_t>(elements_++)] = e;
      prev = next;
    }
    ++members_;
    return first;
  }

  int nodes() const { return nodes_; }
  int elements() const { return elements_; }
  bool complete() const {
    return std::cmp_equal(nodes_, S.nodes) && std::cmp_equal(elements_, S.elements);
  }

 private:
  ntn::ModelSpec<S>& spec_;
  int nodes_ = 0, elements_ = 0, members_ = 0;
};

// A straight beam of S.elements equal elements from `origin` along `axis` (need not be unit),
// nodes numbered 0..S.elements from the origin. Node 0 gets `fixed_first`, the last node
// `fixed_last`. Nodes beyond S.elements (if any) are left for the caller.
template <ntn::Sizes S>
void straight_beam(ntn::ModelSpec<S>& spec, double length, const Material& m, const Section& s,
                   std::uint8_t fixed_first = kFixedAll, std::uint8_t fixed_last = 0,
                   const Vec3& axis = {1, 0, 0}, const Vec3& ref = {0, 0, 1},
                   const Vec3& origin = {0, 0, 0}) {
  static_assert(S.nodes >= S.elements + 1, "a line of N elements needs N + 1 nodes");
  const double n = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
  for (std::size_t k = 0; k <= S.elements; ++k) {
    const double t = length * static_cast<double>(k) / static_cast<double>(S.elements) / n;
    ntn::NodeSpec& node = spec.nodes[k];
    node = {};
    node.x = origin[0] + t * axis[0], node.y = origin[1] + t * axis[1];
    node.z = origin[2] + t * axis[2];
  }
  spec.nodes[0].fixed = fixed_first;
  spec.nodes[S.elements].fixed = fixed_last;
  for (std::size_t k = 0; k < S.elements; ++k) {
    const int i = static_cast<int>(k);
    spec.elements[k] = element(i, i + 1, m, s, ref);
  }
}

// Global index of node DOF d.
constexpr std::size_t dof(int node, int d) {
  return static_cast<std::size_t>(ntn::kDofsPerNode * node + d);
}
constexpr std::size_t dof(std::size_t node, int d) {
  return ntn::kDofsPerNode * node + static_cast<std::size_t>(d);
}

}  // namespace ntn_test
