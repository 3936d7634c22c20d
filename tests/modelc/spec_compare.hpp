// Field-by-field, bit-for-bit comparison of a generated ModelSpec<S> with the ModelDescription
// that load_model gives for the same file (the header round trip).
#pragma once

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <string_view>

#include "ntn/model_spec.hpp"
#include "ntn/modelc/model_description.hpp"

namespace ntn::test {

inline void expect_bits(double a, double b, const char* what, std::size_t i) {
  EXPECT_EQ(std::bit_cast<std::uint64_t>(a), std::bit_cast<std::uint64_t>(b))
      << what << " [" << i << "]: " << a << " vs " << b;
}

template <Sizes S>
void expect_same_spec(const ModelSpec<S>& h, const modelc::ModelDescription& d) {
  const Sizes z = d.sizes();
  ASSERT_EQ(z.nodes, S.nodes);
  ASSERT_EQ(z.elements, S.elements);
  ASSERT_EQ(z.time_functions, S.time_functions);
  ASSERT_EQ(z.time_points, S.time_points);
  ASSERT_EQ(z.loads, S.loads);
  ASSERT_EQ(z.inputs, S.inputs);
  ASSERT_EQ(z.outputs, S.outputs);
  ASSERT_EQ(z.hinges, S.hinges);
  ASSERT_EQ(z.curves, S.curves);
  ASSERT_EQ(z.curve_points, S.curve_points);
  ASSERT_EQ(z.element_loads, S.element_loads);
  ASSERT_EQ(z.hystereses, S.hystereses);
  for (std::size_t i = 0; i < h.nodes.size(); ++i) {
    const NodeSpec &a = h.nodes[i], &b = d.nodes[i];
    expect_bits(a.x, b.x, "node x", i), expect_bits(a.y, b.y, "node y", i);
    expect_bits(a.z, b.z, "node z", i);
    EXPECT_EQ(a.fixed, b.fixed) << i;
    for (std::size_t k = 0; k < a.added.size(); ++k)
      expect_bits(a.added[k], b.added[k], "added", i);
    for (std::size_t k = 0; k < a.u0.size(); ++k) {
      expect_bits(a.u0[k], b.u0[k], "u0", i);
      expect_bits(a.v0[k], b.v0[k], "v0", i);
    }
  }
  for (std::size_t i = 0; i < h.elements.size(); ++i) {
    const ElementSpec &a = h.elements[i], &b = d.elements[i];
    EXPECT_EQ(a.node_i, b.node_i) << i;
    EXPECT_EQ(a.node_j, b.node_j) << i;
    EXPECT_EQ(a.member, b.member) << i;
    const double av[] = {
        a.E,     a.G,     a.rho,  a.A, a.Iy, a.Iz, a.J, a.shear_area_y, a.shear_area_z,
        a.ref_x, a.ref_y, a.ref_z};
    const double bv[] = {
        b.E,     b.G,     b.rho,  b.A, b.Iy, b.Iz, b.J, b.shear_area_y, b.shear_area_z,
        b.ref_x, b.ref_y, b.ref_z};
    for (std::size_t k = 0; k < std::size(av); ++k)
      expect_bits(av[k], bv[k], "element", i);
  }
  for (std::size_t i = 0; i < h.time_points.size(); ++i) {
    expect_bits(h.time_points[i].t, d.time_points[i].t, "t", i);
    expect_bits(h.time_points[i].value, d.time_points[i].value, "value", i);
  }
  for (std::size_t i = 0; i < h.time_functions.size(); ++i) {
    EXPECT_EQ(h.time_functions[i].first, d.time_functions[i].first);
    EXPECT_EQ(h.time_functions[i].count, d.time_functions[i].count);
  }
  for (std::size_t i = 0; i < h.loads.size(); ++i) {
    EXPECT_EQ(h.loads[i].node, d.loads[i].node);
    EXPECT_EQ(h.loads[i].dof, d.loads[i].dof);
    EXPECT_EQ(h.loads[i].time_function, d.loads[i].time_function);
    expect_bits(h.loads[i].value, d.loads[i].value, "load", i);
  }
  for (std::size_t i = 0; i < h.inputs.size(); ++i) {
    EXPECT_EQ(h.inputs[i].kind, d.inputs[i].kind);
    EXPECT_EQ(h.inputs[i].node, d.inputs[i].node);
    EXPECT_EQ(h.inputs[i].dof, d.inputs[i].dof);
    expect_bits(h.inputs[i].scale, d.inputs[i].scale, "input scale", i);
    expect_bits(h.inputs[i].min, d.inputs[i].min, "input min", i);
    expect_bits(h.inputs[i].max, d.inputs[i].max, "input max", i);
    expect_bits(h.inputs[i].factor, d.inputs[i].factor, "input factor", i);
  }
  for (std::size_t i = 0; i < h.outputs.size(); ++i) {
    const OutputSpec &a = h.outputs[i], &b = d.outputs[i];
    EXPECT_EQ(a.kind, b.kind);
    EXPECT_EQ(a.node, b.node);
    EXPECT_EQ(a.node2, b.node2);
    EXPECT_EQ(a.element, b.element);
    EXPECT_EQ(a.end, b.end);
    EXPECT_EQ(a.dof, b.dof);
    EXPECT_EQ(a.hinge, b.hinge);
    expect_bits(a.scale, b.scale, "output scale", i);
  }
  for (std::size_t i = 0; i < h.hinges.size(); ++i) {
    const HingeSpec &a = h.hinges[i], &b = d.hinges[i];
    EXPECT_EQ(a.node1, b.node1) << i;
    EXPECT_EQ(a.node2, b.node2) << i;
    for (std::size_t k = 0; k < 9; ++k)
      expect_bits(a.frame[k], b.frame[k], "hinge frame", i);
    for (std::size_t k = 0; k < 3; ++k)
      expect_bits(a.eccentricity[k], b.eccentricity[k], "hinge eccentricity", i);
    for (std::size_t k = 0; k < 6; ++k) {
      EXPECT_EQ(a.behaviour[k], b.behaviour[k]) << i << " direction " << k;
      expect_bits(a.stiffness[k], b.stiffness[k], "hinge stiffness", i);
      expect_bits(a.dashpot[k], b.dashpot[k], "hinge dashpot", i);
      EXPECT_EQ(a.curve[k], b.curve[k]) << i << " direction " << k;
    }
  }
  for (std::size_t i = 0; i < h.curves.size(); ++i) {
    EXPECT_EQ(h.curves[i].first, d.curves[i].first);
    EXPECT_EQ(h.curves[i].count, d.curves[i].count);
  }
  for (std::size_t i = 0; i < h.curve_points.size(); ++i) {
    expect_bits(h.curve_points[i].d, d.curve_points[i].d, "curve d", i);
    expect_bits(h.curve_points[i].force, d.curve_points[i].force, "curve force", i);
  }
  for (std::size_t i = 0; i < h.element_loads.size(); ++i) {
    EXPECT_EQ(h.element_loads[i].element, d.element_loads[i].element) << i;
    EXPECT_EQ(h.element_loads[i].time_function, d.element_loads[i].time_function) << i;
    for (std::size_t k = 0; k < 12; ++k)
      expect_bits(h.element_loads[i].local[k], d.element_loads[i].local[k], "element load", i);
  }
  for (std::size_t i = 0; i < h.hystereses.size(); ++i) {
    const HysteresisSpec &x = h.hystereses[i], &y = d.hystereses[i];
    EXPECT_EQ(x.rule, y.rule) << i;
    EXPECT_EQ(x.normal, y.normal) << i;
    EXPECT_EQ(x.fixed_if, y.fixed_if) << i;
    EXPECT_EQ(x.circle, y.circle) << i;
    expect_bits(x.mu, y.mu, "mu", i);
    expect_bits(x.cohesion, y.cohesion, "cohesion", i);
    expect_bits(x.yield_pos, y.yield_pos, "yield_pos", i);
    expect_bits(x.yield_neg, y.yield_neg, "yield_neg", i);
    expect_bits(x.hardening, y.hardening, "hardening", i);
    for (std::size_t k = 0; k < 3; ++k)
      expect_bits(x.limits[k], y.limits[k], "limits", i);
    for (std::size_t k = 0; k < 4; ++k) {
      expect_bits(x.backbone_pos[k].d, y.backbone_pos[k].d, "backbone_pos d", i);
      expect_bits(x.backbone_pos[k].force, y.backbone_pos[k].force, "backbone_pos force", i);
      expect_bits(x.backbone_neg[k].d, y.backbone_neg[k].d, "backbone_neg d", i);
      expect_bits(x.backbone_neg[k].force, y.backbone_neg[k].force, "backbone_neg force", i);
    }
  }
  const Settings &a = h.settings, &b = d.settings;
  expect_bits(a.dt, b.dt, "dt", 0);
  expect_bits(a.frame_period, b.frame_period, "frame_period", 0);
  expect_bits(a.alpha, b.alpha, "alpha", 0);
  expect_bits(a.beta, b.beta, "beta", 0);
  for (std::size_t k = 0; k < 3; ++k)
    expect_bits(a.gravity[k], b.gravity[k], "gravity", k);
  EXPECT_EQ(a.gravity_function, b.gravity_function);
  EXPECT_EQ(a.rotary_inertia, b.rotary_inertia);
  EXPECT_EQ(a.allow_unstable, b.allow_unstable);
  EXPECT_EQ(a.hinge_method, b.hinge_method);
  EXPECT_EQ(a.clamp, b.clamp);
  expect_bits(a.penalty_stiffness, b.penalty_stiffness, "penalty_stiffness", 0);
  expect_bits(a.penalty_rotational_stiffness, b.penalty_rotational_stiffness,
              "penalty_rotational_stiffness", 0);
  expect_bits(a.limit_stiffness, b.limit_stiffness, "limit_stiffness", 0);
  expect_bits(a.limit_rotational_stiffness, b.limit_rotational_stiffness,
              "limit_rotational_stiffness", 0);
}

template <std::size_t N>
void expect_same_names(const std::array<std::string_view, N>& h,
                       const std::vector<std::string>& d) {
  ASSERT_EQ(N, d.size());
  for (std::size_t i = 0; i < N; ++i)
    EXPECT_EQ(h[i], d[i]) << i;
}

}  // namespace ntn::test
