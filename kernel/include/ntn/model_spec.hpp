// The model as data: what the model compiler emits (as constexpr) and what `init` reads.
// Plain aggregates only, so a generated header can spell a whole model as one constant.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <type_traits>

#include "ntn/storage.hpp"

namespace ntn {

// Node DOF order (DESIGN §3): ux, uy, uz, rx, ry, rz.
inline constexpr int kDofsPerNode = 6;
enum Dof : std::uint8_t { kUx = 0, kUy, kUz, kRx, kRy, kRz };

struct NodeSpec {
  double x = 0, y = 0, z = 0;                // m
  std::uint8_t fixed = 0;                    // bit d set: DOF d is held at zero (support)
  std::array<double, kDofsPerNode> added{};  // point mass kg (ux,uy,uz), inertia kg m^2 (rx,ry,rz)
  // The run's initial state (initial_state(), integrator.hpp): u_0 in m and rad, v_0 in m/s and
  // rad/s, global axes: the model compiler's static preload plus the file's [initial] values.
  std::array<double, kDofsPerNode> u0{};
  std::array<double, kDofsPerNode> v0{};
};

// How an element's displacements enter its internal force (DESIGN §4, geometry.hpp).
enum class Geometry : std::uint8_t {
  kLinear,        // small displacements: F = T^T K_L T u
  kPDelta,        // plus the chord's second-order strain: the axial force's geometric stiffness
  kLeaning,       // a leaning column: the axial force and its P-Delta, no bending or torsion
  kCorotational,  // large displacements and rotations, small strains (corotational.hpp)
};

// One 2-node frame element with its material and section resolved (DESIGN §4).
struct ElementSpec {
  int node_i = 0, node_j = 0;
  double E = 0, G = 0, rho = 0;         // Pa, Pa, kg/m^3
  double A = 0, Iy = 0, Iz = 0, J = 0;  // m^2, m^4, m^4, m^4
  double shear_area_y = 0;              // m^2, kappa*A for shear along local y; 0 = Euler-Bernoulli
  double shear_area_z = 0;              // m^2, same along local z
  double ref_x = 0, ref_y = 0, ref_z = 1;  // orientation vector: local z lies in plane(x, ref)
  int member = 0;                          // index of the member it was meshed from (for reports)
  Geometry geometry = Geometry::kLinear;
};

struct TimePoint {
  double t = 0;      // s
  double value = 0;  // factor
};

// Piecewise-linear factor through points [first, first+count); held constant outside.
struct TimeFunctionSpec {
  int first = 0;
  int count = 0;
};

inline constexpr int kConstant = -1;  // "no time function": factor 1

struct LoadSpec {
  int node = 0;
  int dof = 0;
  double value = 0;  // N or N m
  int time_function = kConstant;
};

enum class InputKind : std::uint8_t {
  kGroundAcceleration,  // uniform base excitation along `dof` (0..2): load -M iota a_g (S 1, §5)
  kNodalForce,          // force or moment at (node, dof)
};

struct InputSpec {
  InputKind kind = InputKind::kGroundAcceleration;
  int node = 0;         // kNodalForce only
  int dof = 0;          // direction (0..2) or node DOF (0..5)
  double scale = 1;     // input value x scale = SI value (e.g. 9.80665 for records in g)
  double min = -1e300;  // accepted range of the raw input value (before scale and factor)
  double max = 1e300;
  double factor = 1;  // kGroundAcceleration: the model file's `scale`, a factor on the motion
                      // (a_g = value x scale x factor); 1 for a nodal force, whose model file
                      // `scale` is its unit (scale above)
};

enum class OutputKind : std::uint8_t {
  kDisplacement,          // node DOF, m or rad
  kVelocity,              // node DOF, m/s or rad/s
  kAcceleration,          // node DOF, relative to the ground, m/s^2 or rad/s^2
  kElementForce,          // element end force in local axes: component 0..5 = N, Vy, Vz, T, My, Mz,
                          // K_L T u minus the element's own loads (ElementLoadSpec)
  kDrift,                 // (u[node2] - u[node]) / height in DOF `dof`: inter-storey drift ratio
  kReaction,              // sum over supported DOFs `dof` of (F - P): support reaction, N or N m
  kAbsoluteAcceleration,  // node DOF, a_n plus the ground acceleration: what an accelerometer reads
  kHingeForce,            // hinge `hinge`, local direction `dof`: force on node 1 in the hinge
                          // frame (constraint force if rigid, spring force otherwise), N or N m
  kHingeDisplacement,     // hinge `hinge`, local direction `dof`: relative displacement d_L
  kHingePlastic,          // hinge `hinge`, local direction `dof` (kPlastic): plastic deformation
  kHingeDissipated,       // the same: hysteretic energy dissipated so far, J
  kHingeLevel,            // the same: performance level reached, 0..4 (performance_level())
  kHingeVelocity,         // hinge `hinge`, local direction `dof`: relative velocity at t_n (the
                          // slip velocity of a sliding direction), m/s or rad/s
  kHingeSlipState,        // the same (kRigidPlastic): 0 sticks, +1 / -1 slides at its limit in
                          // the positive / negative sense, 2 free (broken, or fixed_if released)
};

// NTN hinges (DESIGN §7). Node 1 is the member end ("slave"), node 2 the joint ("master") or
// the ground (a support with its own frame). Local directions: ux, uy, uz, rx, ry, rz of the
// hinge frame.
inline constexpr int kGround = -1;

enum class HingeBehaviour : std::uint8_t {
  kRigid,    // no relative motion (NTN coupling, or a penalty spring with the `penalty` method)
  kFree,     // no force
  kLinear,   // spring `stiffness` and optional dashpot `dashpot`
  kCurve,    // piecewise-linear force(deformation) `curve`; segments at least as stiff as the
             // limit stiffness are rigid branches (a gap or a stop)
  kPlastic,  // hysteretic: elastic `stiffness`, its law in `hysteresis` (a HysteresisSpec:
             // bilinear with kinematic hardening, or a backbone with a hysteresis rule), optional
             // `dashpot` (bilinear only); its history lives in State (hysteresis.hpp)
  kRigidPlastic,  // rigid until its force reaches the yield of its `hysteresis` (a kBilinear
                  // HysteresisSpec, hardening 0), or its friction limit mu max(0, -N) + c
                  // (HysteresisSpec::normal), then it slides at that force (slip.hpp):
                  // exact stick and slip under ntn_exact, a bilinear spring of the penalty
                  // stiffness under penalty, refused by ntn_paper; its slip is State::plastic.
                  // `stiffness` > 0: linear hardening with the slip (a spring of that stiffness
                  // in parallel; kBilinear only). Also fixed_if (HysteresisSpec::fixed_if) and
                  // failure (kBrittle: breaks at its first slide)
};

// Each method is a struct in its own header (ntn_exact.hpp, ntn_paper.hpp, penalty.hpp); only
// hinge_methods.hpp turns a value into its method.
enum class HingeMethod : std::uint8_t {
  kNtnExact,  // the constraint forest of DESIGN §7.1 (default)
  kNtnPaper,  // the seed's algorithm literally (S 17-37); aligned, zero eccentricity
  kPenalty,   // rigid directions as stiff springs K = B^T K_p B
};

// The velocity the damping forces take, alpha M and the hinge dashpots (beta K_el stays at
// v_{n-1/2} either way).
enum class DampingVelocity : std::uint8_t {
  kCentral,  // v_n = v_{n-1/2} + dt/2 a_n: (M + C dt/2) a_n = R_n - C v_{n-1/2}, second order
  kLagged,   // v_{n-1/2} (S 3-4): first order
};

enum class ClampRule : std::uint8_t {
  kMomentum,  // project a pair onto its rigid branch keeping its mass-weighted centre
  kPaper,     // scale both local displacements by d_lim / d (S 33)
};

struct HingeSpec {
  int node1 = 0;
  int node2 = 0;                                           // or kGround
  std::array<double, 9> frame{1, 0, 0, 0, 1, 0, 0, 0, 1};  // rows: hinge axes x, y, z in global
  std::array<double, 3> eccentricity{};                    // m, e = x2 - x1 in global axes
  std::array<HingeBehaviour, kDofsPerNode> behaviour{};    // default: rigid in all six
  std::array<double, kDofsPerNode> stiffness{};            // N/m or N m/rad (kLinear, kPlastic;
                                                 // kRigidPlastic: its hardening with the slip)
  std::array<double, kDofsPerNode> dashpot{};  // N s/m or N m s/rad (kLinear)
  std::array<int, kDofsPerNode> curve{};       // index into curves (kCurve)
  std::array<int, kDofsPerNode>
      hysteresis{};  // index into hystereses (kPlastic), one per direction
};

struct CurvePoint {
  double d = 0;      // m or rad, relative displacement in the hinge frame
  double force = 0;  // N or N m, force on node 1 in the hinge frame
};

// How a hysteretic direction (kPlastic) loads, unloads and reloads (hysteresis.hpp).
enum class HysteresisRule : std::uint8_t {
  kBilinear,      // yield_pos/yield_neg, hardening: the elastic range translates (kinematic)
  kKinematic,     // a backbone; each sense bounded by its envelope, the first post-yield
                  // segment extended back across the origin (steel: unloading at k, the elastic
                  // range translates); strength past the capping point never comes back
  kPeakOriented,  // a backbone; unloading at k to zero force, reloading toward the point of the
                  // largest excursion so far in that sense (concrete, timber)
  kBrittle,       // linear (kPlastic: its stiffness; kRigidPlastic: rigid) until its force first
                  // passes yield_pos or -yield_neg, then no force for the rest of the run (a
                  // bolt that breaks; State::first_slip says when): laws/brittle.hpp
  kImk,           // modified Ibarra-Medina-Krawinkler, bilinear: a backbone with capping,
                  // post-capping and residual strength that deteriorates with the energy it
                  // dissipates (laws/imk.hpp; its values in `parameters`)
};

// A law's own values beyond the shared ones (HysteresisSpec::parameters, HysteresisData::p),
// by the names its header gives them.
inline constexpr std::size_t kLawParameters = 18;
using LawParameters = std::array<double, kLawParameters>;

// A hysteretic hinge direction's law (kPlastic). Each entry belongs to one direction; its index
// is the direction's slot in State::plastic, State::dissipated, State::plastic_peak and
// State::excursion.
// kBilinear: yield force or moment in the positive and the negative sense (both > 0, N or N m)
// and the hardening ratio b in [0, 1): the tangent after yield is b k (kinematic hardening: the
// elastic range, of width yield_pos + yield_neg, moves with the back force).
// kKinematic, kPeakOriented: the monotonic envelope of each sense (ASCE 41 / FEMA 356), as
// magnitudes, after A = (0, 0): B the yield point (on the elastic line: force = k d), C the
// capping point, D the drop to the residual strength, E the ultimate deformation, past which the
// direction has no strength left in either sense and transmits no force. yield_pos and
// yield_neg hold B's forces, hardening 0.
// `limits`: the acceptance criteria on the peak plastic deformation |d_p| (ASCE 41 / FEMA 356:
// immediate occupancy, life safety, collapse prevention), all three or none (zeros);
// performance_level() (hysteresis.hpp) grades a direction by them.
struct HysteresisSpec {
  double yield_pos = 0;
  double yield_neg = 0;
  double hardening = 0;
  std::array<double, 3> limits{};  // m or rad: io, ls, cp; 0, 0, 0: none
  HysteresisRule rule = HysteresisRule::kBilinear;
  std::array<CurvePoint, 4> backbone_pos{};  // B, C, D, E (kKinematic, kPeakOriented)
  std::array<CurvePoint, 4> backbone_neg{};  // the same in the negative sense, as magnitudes
  // Friction (a kRigidPlastic direction, slip.hpp): with `normal` >= 0 its limit in both senses
  // is mu max(0, -N) + cohesion, N the force at t_n of direction `normal` of the same hinge
  // (rigid, a spring or a curve; N < 0 presses the nodes together: the spring convention
  // f = k d, d < 0 when they approach along the normal axis), and the yields are not used.
  int normal = -1;
  double mu = 0;
  double cohesion = 0;  // N or N m
  // The friction circle: the other tangential direction (0..5) of the same hinge, a friction
  // direction with the same normal, mu and cohesion whose `circle` is this one; their one limit
  // mu max(0, -N) + cohesion bounds the resultant of the two forces. -1: none.
  int circle = -1;
  // fixed_if (a kRigidPlastic direction, slip.hpp): -1 (+1) when the direction is rigid while
  // the force at t_n of direction `normal` of the same hinge is negative (positive) and free
  // otherwise (RFEM's "fixed if N-"); mu, cohesion and the yields are not used.
  int fixed_if = 0;
  LawParameters parameters{};  // a law's own values, named by its header (0: unused)
};

// A distributed load on one element (a member load's part on it, the model compiler's
// [[member_loads]]): its consistent nodal forces in the element's local axes [F_i, M_i, F_j, M_j]
// (the order of beam_local_force), times the time function. The nodal loads (LoadSpec) carry
// them into the step; the element-force outputs subtract them, so that a channel reads the
// element's end forces under its load, K_L T u - f (the fixed-end forces when u = 0).
struct ElementLoadSpec {
  int element = 0;
  int time_function = kConstant;
  std::array<double, 12> local{};  // N and N m, local axes
};

// Points [first, first + count) of a force-deformation curve, deformation strictly increasing.
struct CurveSpec {
  int first = 0;
  int count = 0;
};

struct OutputSpec {
  OutputKind kind = OutputKind::kDisplacement;
  int node = 0;      // node, or lower node of a drift
  int node2 = 0;     // upper node of a drift
  int element = 0;   // kElementForce
  int end = 0;       // kElementForce: 0 = start (node_i), 1 = end (node_j)
  int dof = 0;       // DOF or force component
  double scale = 1;  // output = SI value x scale; a drift stores 1/height here
  int hinge = 0;     // kHingeForce, kHingeDisplacement
};

struct Settings {
  double dt = 0;               // s, resolved by the model compiler ("auto" -> number)
  double frame_period = 1e-3;  // s, the I/O frame that dt divides into substeps
  double alpha = 0;            // 1/s, mass-proportional damping: C = alpha M + beta K_el
  double beta = 0;             // s, stiffness-proportional damping (K_el: the elements')
  DampingVelocity damping_velocity = DampingVelocity::kCentral;  // alpha M's and the dashpots'
  std::array<double, 3> gravity{};  // m/s^2, applied as M g on translations
  int gravity_function = kConstant;
  bool rotary_inertia = false;  // add rho I l / 2 to the bending rotation masses (DESIGN §4)
  bool allow_unstable = false;  // accept dt above the stable step (failure testing only)
  HingeMethod hinge_method = HingeMethod::kNtnExact;
  ClampRule clamp = ClampRule::kMomentum;
  double penalty_stiffness = 0;             // N/m, rigid translations with kPenalty
  double penalty_rotational_stiffness = 0;  // N m/rad, rigid rotations with kPenalty
  double limit_stiffness = 0;               // N/m: curve slopes at least this are rigid branches
  double limit_rotational_stiffness = 0;    // N m/rad, the same for rotations
};

// The stiffness `penalty` gives rigid hinge direction k (0-2 translations, N/m; 3-5 rotations,
// N m/rad): the kernel's penalty method and modal analysis' penalty springs read it here.
constexpr double penalty_stiffness(const Settings& s, std::size_t k) {
  return k < 3 ? s.penalty_stiffness : s.penalty_rotational_stiffness;
}

// The slope from which a segment of a curve in hinge direction k is a rigid branch (seed Fig. 2):
// the limit stiffness of translations or rotations, 1e300 (no limit) when it is not positive.
// The kernel, the model compiler and modal analysis split curves with it.
constexpr double branch_slope_limit(const Settings& s, std::size_t k) {
  const double lim = k < 3 ? s.limit_stiffness : s.limit_rotational_stiffness;
  return lim > 0 ? lim : 1e300;
}

// An array of a model's spec: a std::array in a compiled spec (a generated header spells the
// whole model as one constant), a view of the caller's arrays in a run-time one.
template <class T, Sizes S, std::size_t N>
using SpecArray = std::conditional_t<S.runtime, std::span<const T>, std::array<T, N>>;

// Everything a model is: at compile-time sizes, or (kRunTime) views of a run-time description.
template <Sizes S>
struct ModelSpec {
  static constexpr Sizes kSizes = S;
  SpecArray<NodeSpec, S, S.nodes> nodes{};
  SpecArray<ElementSpec, S, S.elements> elements{};
  SpecArray<TimePoint, S, S.time_points> time_points{};
  SpecArray<TimeFunctionSpec, S, S.time_functions> time_functions{};
  SpecArray<LoadSpec, S, S.loads> loads{};
  SpecArray<InputSpec, S, S.inputs> inputs{};
  SpecArray<OutputSpec, S, S.outputs> outputs{};
  SpecArray<HingeSpec, S, S.hinges> hinges{};
  SpecArray<CurveSpec, S, S.curves> curves{};
  SpecArray<CurvePoint, S, S.curve_points> curve_points{};
  SpecArray<ElementLoadSpec, S, S.element_loads> element_loads{};
  SpecArray<HysteresisSpec, S, S.hystereses> hystereses{};
  Settings settings{};
};

// A size-free view of a model, for code that runs on models of any size (model compiler,
// modal analysis, reports). Produced from a ModelSpec or from a run-time description.
struct SpecView {
  std::span<const NodeSpec> nodes;
  std::span<const ElementSpec> elements;
  std::span<const TimePoint> time_points;
  std::span<const TimeFunctionSpec> time_functions;
  std::span<const LoadSpec> loads;
  std::span<const InputSpec> inputs;
  std::span<const OutputSpec> outputs;
  std::span<const HingeSpec> hinges;
  std::span<const CurveSpec> curves;
  std::span<const CurvePoint> curve_points;
  std::span<const ElementLoadSpec> element_loads;
  std::span<const HysteresisSpec> hystereses;
  Settings settings;
};

template <Sizes S>
constexpr SpecView view(const ModelSpec<S>& spec) {
  return {spec.nodes,   spec.elements,     spec.time_points,   spec.time_functions,
          spec.loads,   spec.inputs,       spec.outputs,       spec.hinges,
          spec.curves,  spec.curve_points, spec.element_loads, spec.hystereses,
          spec.settings};
}

// The elements whose chord has second-order strain, p_delta and leaning (Sizes::geometric).
constexpr std::size_t geometric_elements(std::span<const ElementSpec> elements) {
  std::size_t n = 0;
  for (const ElementSpec& e : elements)
    n += e.geometry == Geometry::kPDelta || e.geometry == Geometry::kLeaning ? 1 : 0;
  return n;
}

// The corotational elements (Sizes::corotational).
constexpr std::size_t corotational_elements(std::span<const ElementSpec> elements) {
  std::size_t n = 0;
  for (const ElementSpec& e : elements)
    n += e.geometry == Geometry::kCorotational ? 1 : 0;
  return n;
}

// The hinges that turn with their nodes (corotational geometry): a hinge between two nodes either
// of which a corotational element reaches. Its axes and offset follow node 1's rotation and its
// rotations are node 2's relative to node 1 (hinge.hpp's hinge_turned); what it may hold is
// turning_hinge_check's (hinge_methods.hpp). A hinge to the ground keeps the ground's axes. The
// first such node of h, or -1.
constexpr int corotational_hinge_node(const HingeSpec& h, std::span<const ElementSpec> elements) {
  if (h.node2 == kGround) return -1;
  for (const ElementSpec& e : elements) {
    if (e.geometry != Geometry::kCorotational) continue;
    for (const int n : {h.node1, h.node2}) {
      if (n == e.node_i || n == e.node_j) return n;
    }
  }
  return -1;
}

// The sizes of a model given as a view (a run-time description): the counts of its arrays.
constexpr Sizes sizes_of(const SpecView& v) {
  Sizes s;
  s.nodes = v.nodes.size();
  s.elements = v.elements.size();
  s.time_functions = v.time_functions.size();
  s.time_points = v.time_points.size();
  s.loads = v.loads.size();
  s.inputs = v.inputs.size();
  s.outputs = v.outputs.size();
  s.hinges = v.hinges.size();
  s.curves = v.curves.size();
  s.curve_points = v.curve_points.size();
  s.element_loads = v.element_loads.size();
  s.hystereses = v.hystereses.size();
  s.geometric = geometric_elements(v.elements);
  s.corotational = corotational_elements(v.elements);
  return s;
}

// The run-time spec of a view: the same arrays, for init() into run-time storage.
constexpr ModelSpec<kRunTime> runtime_spec(const SpecView& v) {
  ModelSpec<kRunTime> spec;
  spec.nodes = v.nodes;
  spec.elements = v.elements;
  spec.time_points = v.time_points;
  spec.time_functions = v.time_functions;
  spec.loads = v.loads;
  spec.inputs = v.inputs;
  spec.outputs = v.outputs;
  spec.hinges = v.hinges;
  spec.curves = v.curves;
  spec.curve_points = v.curve_points;
  spec.element_loads = v.element_loads;
  spec.hystereses = v.hystereses;
  spec.settings = v.settings;
  return spec;
}

}  // namespace ntn
