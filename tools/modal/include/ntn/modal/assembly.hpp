// Global stiffness of a model's beam elements, entry by entry, from the kernel's own element
// functions (ntn::beam_geometry, ntn::beam_stiffness, ntn::beam_global_stiffness: DESIGN §4), so
// that modal analysis and the tests' dense reference solutions use exactly the discrete model the
// kernel integrates. Header-only, no Eigen: the caller decides the storage (a dense matrix in
// tests, sparse triplets in ntn::modal). The lumped mass is the kernel's ntn::assemble_lumped_mass,
// which lumped_mass() calls with storage of its own (the one function here that allocates).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "ntn/beam.hpp"
#include "ntn/geometry.hpp"
#include "ntn/init.hpp"
#include "ntn/model.hpp"
#include "ntn/model_spec.hpp"

namespace ntn::modal {

// The kernel's lumped masses of a spec, out[6 n + d] (ntn::assemble_lumped_mass), summed in the
// model's element order (ntn::spec_element_order), as init() sums them.
inline std::vector<double> lumped_mass(const SpecView& spec) {
  std::vector<OrderElement> elements(spec.elements.size());
  std::vector<std::int32_t> order(spec.elements.size());
  spec_element_order(spec, elements, order);
  std::vector<double> mass(kDofsPerNode * spec.nodes.size());
  assemble_lumped_mass(spec, order, mass);
  return mass;
}

// Calls add(row, column, value) for every entry of every element's 12 x 12 global stiffness
// T^T K_L T, with global DOF indices 6 node + d; entries that are exactly zero are skipped.
// Returns the index of the first element with a bad geometry (zero length, orientation vector
// along the member) or bad properties, with nothing added for it or after it; -1 when all are
// fine.
template <class Add>
int for_each_element_stiffness(const SpecView& spec, Add&& add) {
  for (std::size_t i = 0; i < spec.elements.size(); ++i) {
    const ElementSpec& e = spec.elements[i];
    if (e.node_i < 0 || e.node_j < 0 || static_cast<std::size_t>(e.node_i) >= spec.nodes.size() ||
        static_cast<std::size_t>(e.node_j) >= spec.nodes.size() || !beam_properties_valid(e))
      return static_cast<int>(i);
    const BeamGeometry g = beam_geometry(spec.nodes[static_cast<std::size_t>(e.node_i)],
                                         spec.nodes[static_cast<std::size_t>(e.node_j)], e);
    if (g.check != ElementCheck::kOk) return static_cast<int>(i);
    BeamData b;
    b.node_i = e.node_i, b.node_j = e.node_j;
    b.rotation = g.rotation;
    b.k = beam_stiffness(e, g.length);
    const Matrix12 K = beam_global_stiffness(b);
    const int node[2] = {e.node_i, e.node_j};
    for (int r = 0; r < 12; ++r) {
      for (int c = 0; c < 12; ++c) {
        const double v = K[static_cast<std::size_t>(r * 12 + c)];
        if (v == 0.0) continue;
        add(kDofsPerNode * node[r / 6] + r % 6, kDofsPerNode * node[c / 6] + c % 6, v);
      }
    }
  }
  return -1;
}

// The elements with second-order geometry (geometry.hpp) as the step reads them, in element order
// (their stable-step limits left at 0: not for a step).
inline std::vector<GeometricElement> geometric_elements(const SpecView& spec) {
  std::vector<GeometricElement> out;
  for (std::size_t i = 0; i < spec.elements.size(); ++i) {
    const ElementSpec& e = spec.elements[i];
    if (e.geometry == Geometry::kLinear) continue;
    out.push_back(geometric_element(e, static_cast<std::int32_t>(i),
                                    spec.nodes[static_cast<std::size_t>(e.node_i)],
                                    spec.nodes[static_cast<std::size_t>(e.node_j)]));
  }
  return out;
}

// Calls add(row, column, value) for every entry of the geometric stiffness K_g(N(u)) of the
// elements with second-order geometry at the displacement u (6 per node: their axial forces N
// as the step computes them, ntn::geometric_force), skipping exact zeros.
template <class Add>
void for_each_geometric_stiffness(const std::vector<GeometricElement>& elements,
                                  const std::vector<double>& u, Add&& add) {
  for (const GeometricElement& ge : elements) {
    const Matrix12 K = geometric_stiffness(ge, geometric_force(ge, u.data()).normal);
    const int dof[2] = {ge.dof_i, ge.dof_j};
    for (int r = 0; r < 12; ++r) {
      for (int c = 0; c < 12; ++c) {
        const double v = K[static_cast<std::size_t>(r * 12 + c)];
        if (v != 0.0) add(dof[r / 6] + r % 6, dof[c / 6] + c % 6, v);
      }
    }
  }
}

}  // namespace ntn::modal
