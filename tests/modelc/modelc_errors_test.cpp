// One test per error message of the model compiler: each bad model under tests/modelc/bad/
// must give its errors at the exact line and column, with the key and the message.
// The positions were checked by hand against the fixture text (the value, key or table header
// they name); the table below is the specification.
#include <gtest/gtest.h>

#include <ostream>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "ntn/modelc/load_model.hpp"

namespace modelc_errors_test {

using ntn::modelc::Diagnostic;
using ntn::modelc::load_model;

std::string bad(const std::string& name) {
  return std::string(NTN_MODELC_BAD_DIR) + "/" + name;
}

struct Expected {
  const char* test;  // test name
  const char* file;  // fixture under bad/
  int line, column;
  const char* key;
  const char* fragment;  // part of the message
};

// clang-format off
const Expected kExpected[] = {
  {"SyntaxError", "syntax.toml", 5, 2, "", "TOML syntax: Error while parsing array: encountered end-of-file"},
  // Unknown key, in every kind of table, pointing at the key itself.
  {"UnknownKeyRoot", "unknown_key.toml", 2, 1, "colour", "unknown key 'colour' (this table takes: model, materials"},
  {"UnknownKeyModel", "unknown_key.toml", 6, 1, "model.speed", "unknown key 'speed'"},
  {"UnknownKeyDamping", "unknown_key.toml", 11, 1, "model.damping.zeta", "unknown key 'zeta' (this table takes: alpha, beta, ratio, frequency, frequencies, modes)"},
  {"UnknownKeyMaterial", "unknown_key.toml", 18, 1, "materials[0].yield", "unknown key 'yield' (this table takes: id, E, G, nu, rho)"},
  {"UnknownKeySection", "unknown_key.toml", 26, 1, "sections[0].Wy", "unknown key 'Wy'"},
  {"UnknownKeyNode", "unknown_key.toml", 31, 1, "nodes[0].label", "unknown key 'label' (this table takes: id, xyz)"},
  {"UnknownKeyMember", "unknown_key.toml", 42, 1, "members[0].hinge", "unknown key 'hinge'"},
  {"UnknownKeySupport", "unknown_key.toml", 47, 1, "supports[0].spring", "unknown key 'spring' (this table takes: node, fix, axes)"},
  {"UnknownKeyPointMass", "unknown_key.toml", 52, 1, "point_masses[0].weight", "unknown key 'weight'"},
  {"UnknownKeyTimeFunction", "unknown_key.toml", 57, 1, "time_functions[0].kind", "unknown key 'kind' (this table takes: id, points)"},
  {"UnknownKeyLoad", "unknown_key.toml", 63, 1, "loads[0].factor", "unknown key 'factor'"},
  {"UnknownKeyGroundInput", "unknown_key.toml", 69, 1, "inputs[0].node", "unknown key 'node' (this table takes: name, kind, direction, units, scale, min, max)"},
  {"UnknownKeyForceInput", "unknown_key.toml", 76, 1, "inputs[1].units", "unknown key 'units' (this table takes: name, kind, node, dof, scale, min, max)"},
  {"UnknownKeyNodeOutput", "unknown_key.toml", 83, 1, "outputs[0].units", "unknown key 'units' (this table takes: name, kind, node, dof, alarm, alarm_hysteresis)"},
  {"UnknownKeyForceOutput", "unknown_key.toml", 91, 1, "outputs[1].node", "unknown key 'node' (this table takes: name, kind, member, end, component, alarm, alarm_hysteresis)"},
  {"UnknownKeyDriftOutput", "unknown_key.toml", 98, 1, "outputs[2].height", "unknown key 'height' (this table takes: name, kind, nodes, direction, alarm, alarm_hysteresis)"},
  {"UnknownKeyReactionOutput", "unknown_key.toml", 104, 1, "outputs[3].node", "unknown key 'node' (this table takes: name, kind, direction, alarm, alarm_hysteresis)"},
  // Missing required key or table: at the table's header.
  {"MissingKey", "missing_key.toml", 5, 1, "materials[0].E", "missing required key 'E'"},
  {"MissingLoadDof", "load_missing_dof.toml", 36, 1, "loads[0].dof", "missing required key 'dof' (or give force = [Fx, Fy, Fz, Mx, My, Mz])"},
  {"MissingModelTable", "missing_model.toml", 1, 1, "model", "missing required table [model]"},
  // Wrong types.
  {"WrongTypeBoolean", "wrong_type.toml", 4, 18, "model.rotary_inertia", "expected a boolean, got a string"},
  {"WrongTypeString", "wrong_type.toml", 7, 6, "materials[0].id", "expected a string, got an integer"},
  {"WrongTypeNumber", "wrong_type.toml", 8, 5, "materials[0].E", "expected a number, got a string"},
  {"WrongTypeInteger", "wrong_type.toml", 20, 6, "nodes[0].id", "expected an integer, got a floating-point number"},
  {"WrongTypeArray", "wrong_type.toml", 25, 7, "nodes[1].xyz", "expected an array of 3 values, got a string"},
  {"WrongArrayLength", "wrong_type.toml", 29, 9, "members[0].nodes", "expected 2 values, got 3"},
  {"WrongArrayLengthXyz", "array_length.toml", 20, 7, "nodes[0].xyz", "expected 3 values, got 2"},
  {"WrongTypeArrayOfTables", "wrong_table_type.toml", 2, 13, "materials", "expected an array of tables ([[materials]]), got an integer"},
  {"WrongTypeTableItem0", "wrong_table_type.toml", 3, 10, "nodes[0]", "expected a table, got an integer"},
  {"WrongTypeTableItem1", "wrong_table_type.toml", 3, 13, "nodes[1]", "expected a table, got an integer"},
  {"WrongTypeDampingTable", "wrong_table_type.toml", 7, 11, "model.damping", "expected a table ([model.damping]), got a floating-point number"},
  {"WrongTypeModelTable", "model_not_table.toml", 2, 9, "model", "expected a table ([model]), got a string"},
  // Values out of range.
  {"NonFinite", "non_finite.toml", 7, 5, "materials[0].E", "must be a finite number"},
  {"NonPositiveE", "non_positive.toml", 7, 5, "materials[0].E", "must be positive (got -2.1e+11)"},
  {"NonPositiveG", "non_positive.toml", 8, 5, "materials[0].G", "must be positive (got 0)"},
  {"NonPositiveRho", "non_positive.toml", 9, 7, "materials[0].rho", "must be positive (got -7850)"},
  {"NonPositiveA", "non_positive.toml", 13, 5, "sections[0].A", "must be positive (got 0)"},
  {"NonPositiveIy", "non_positive.toml", 14, 6, "sections[0].Iy", "must be positive (got -0.0001)"},
  {"NonPositiveIz", "non_positive.toml", 15, 6, "sections[0].Iz", "must be positive (got 0)"},
  {"NonPositiveJ", "non_positive.toml", 16, 5, "sections[0].J", "must be positive (got -1e-06)"},
  {"Negative", "negative.toml", 38, 8, "point_masses[0].mass", "must not be negative (got -10)"},
  {"DivisionsBelowOne", "divisions.toml", 35, 13, "members[0].divisions", "must be at least 1 (got 0)"},
  {"DivisionsTooMany", "divisions.toml", 42, 13, "members[1].divisions", "must be at most 1000000 (got 2000000)"},
  {"NuRange", "nu_range.toml", 8, 6, "materials[0].nu", "must be greater than -1 and less than 0.5 (got 0.7)"},
  {"BadChoice", "bad_choice.toml", 38, 7, "loads[0].dof", "must be one of \"ux\", \"uy\", \"uz\", \"rx\", \"ry\", \"rz\" (got \"uw\")"},
  {"BadFix", "bad_fix.toml", 34, 7, "supports[0].fix", "must be \"all\", \"pinned\" or an array of DOF names"},
  {"BadModelName", "bad_name.toml", 3, 8, "model.name", "must be a C++ identifier"},
  {"DtString", "dt_string.toml", 4, 6, "model.dt", "must be \"auto\" or a number of seconds (got \"fast\")"},
  {"InputRange", "input_range.toml", 41, 7, "inputs[0].min", "min = 2 must be less than max = -2"},
  // A ground acceleration's scale, a factor on the motion: finite, not 0, a number.
  {"InputScaleZero", "input_scale.toml", 40, 9, "inputs[0].scale", "must be a finite number other than 0 (got 0)"},
  {"InputScaleString", "input_scale.toml", 46, 9, "inputs[1].scale", "expected a number, got a string"},
  {"InputScaleNan", "input_scale.toml", 52, 9, "inputs[2].scale", "must be a finite number"},
  {"InputScaleInf", "input_scale.toml", 59, 9, "inputs[3].scale", "must be a finite number"},
  // Output limit alarms: at the value.
  {"OutputAlarmZero", "output_alarm.toml", 42, 9, "outputs[0].alarm", "must be positive (got 0)"},
  {"OutputAlarmNegative", "output_alarm.toml", 50, 9, "outputs[1].alarm", "must be positive (got -5)"},
  {"OutputAlarmInfinite", "output_alarm.toml", 56, 9, "outputs[2].alarm", "must be a finite number"},
  {"OutputAlarmWrongType", "output_alarm.toml", 63, 9, "outputs[3].alarm", "expected a number, got a string"},
  {"OutputAlarmHysteresisAlone", "output_alarm.toml", 70, 20, "outputs[4].alarm_hysteresis", "alarm_hysteresis needs an alarm: give alarm = LIMIT in this output"},
  {"OutputAlarmHysteresisNotBelow", "output_alarm.toml", 78, 20, "outputs[5].alarm_hysteresis", "alarm_hysteresis = 0.01 must be less than alarm = 0.01 (the alarm goes off below alarm - hysteresis)"},
  {"OutputAlarmHysteresisNegative", "output_alarm.toml", 86, 20, "outputs[6].alarm_hysteresis", "must not be negative (got -0.001)"},
  // Keys that exclude or need each other.
  {"Conflict", "conflict.toml", 9, 6, "materials[0].nu", "cannot be given together with 'G'"},
  {"KappaWithoutTimoshenko", "kappa_without_timoshenko.toml", 17, 11, "sections[0].kappa_y", "only applies with shear = \"timoshenko\""},
  {"FrequencyWithAlpha", "damping_alpha_frequency.toml", 7, 13, "model.damping.frequency", "only applies with 'ratio'"},
  // Rayleigh damping (C = alpha M + beta K_el).
  {"DampingBetaNegative", "damping_beta_negative.toml", 6, 8, "model.damping.beta", "must not be negative (got -0.0001)"},
  {"DampingBetaWithRatio", "damping_beta_ratio.toml", 7, 9, "model.damping.ratio", "cannot be given together with 'beta'"},
  {"DampingModesWithAlpha", "damping_modes_with_alpha.toml", 7, 9, "model.damping.modes", "only applies with 'ratio'"},
  {"DampingFrequencyAndFrequencies", "damping_frequency_frequencies.toml", 8, 15, "model.damping.frequencies", "cannot be given together with 'frequency'"},
  {"DampingFrequenciesEqual", "damping_frequencies_equal.toml", 7, 15, "model.damping.frequencies", "the two frequencies are equal (3 Hz, to 1e-9): Rayleigh damping needs two different ones"},
  {"DampingFrequenciesNotPositive", "damping_frequencies_nonpositive.toml", 7, 15, "model.damping.frequencies", "must be positive (got [0, 5] Hz)"},
  {"DampingFrequenciesBeyondDouble", "damping_frequencies_beyond.toml", 7, 15, "model.damping.frequencies", "ratio = 1e+300 at [1e+10, 2e+10] Hz gives alpha = inf 1/s, beta = 1.06103e+289 s: beyond double"},
  {"DampingModesSame", "damping_modes_same.toml", 7, 9, "model.damping.modes", "the two modes are the same (2): Rayleigh damping needs two different ones"},
  {"DampingModeZero", "damping_modes_zero.toml", 7, 10, "model.damping.modes[0]", "must be at least 1 (got 0)"},
  {"DampingModeBeyondTheModel", "damping_modes_beyond.toml", 7, 9, "model.damping.modes", "mode 40 asked for, but the model has 6 modes"},
  {"DampingModesEqualFrequency", "damping_modes_equal.toml", 8, 9, "model.damping.modes", "modes 2 and 3 have the same frequency (195.962 Hz, to 1e-9)"},
  {"DampingModeRigidBody", "damping_modes_rigid.toml", 7, 9, "model.damping.modes", "mode 1 has zero frequency (a rigid-body motion)"},
  // Time functions.
  {"TimeFunctionEmpty", "time_function_empty.toml", 38, 10, "time_functions[0].points", "expected an array of [t, value] points (at least one), got an empty array"},
  {"TimeFunctionNotIncreasing", "time_function_order.toml", 38, 35, "time_functions[0].points[2]", "t = 1 s does not come after the previous point's t = 1 s: times must increase strictly"},
  // References.
  {"UnknownTimeFunction", "unknown_reference.toml", 5, 20, "model.gravity_function", "unknown time function 'quake'"},
  {"UnknownMaterial", "unknown_reference.toml", 31, 12, "members[0].material", "unknown material 'S235'"},
  {"UnknownSection", "unknown_reference.toml", 38, 11, "members[1].section", "unknown section 'IPE999'"},
  {"UnknownNode", "unknown_reference.toml", 43, 9, "members[2].nodes", "unknown node 7"},
  {"UnknownMember", "unknown_reference.toml", 54, 10, "outputs[0].member", "unknown member 'B9'"},
  // Duplicates, at the repeated id.
  {"DuplicateMaterial", "duplicate.toml", 12, 6, "materials[1].id", "duplicate material id 'S' (first defined at line 6)"},
  {"DuplicateSection", "duplicate.toml", 25, 6, "sections[1].id", "duplicate section id 'H' (first defined at line 18)"},
  {"DuplicateNode", "duplicate.toml", 40, 6, "nodes[2].id", "duplicate node id 2 (first defined at line 36)"},
  {"DuplicateMember", "duplicate.toml", 50, 6, "members[1].id", "duplicate member id 'M1' (first defined at line 44)"},
  {"DuplicateTimeFunction", "duplicate.toml", 64, 6, "time_functions[1].id", "duplicate time function id 'ramp' (first defined at line 60)"},
  {"DuplicateInput", "duplicate.toml", 73, 8, "inputs[1].name", "duplicate input name 'ag' (first defined at line 68)"},
  {"DuplicateOutput", "duplicate.toml", 84, 8, "outputs[1].name", "duplicate output name 'tip' (first defined at line 78)"},
  {"DuplicateSupport", "duplicate_support.toml", 37, 8, "supports[1].node", "node 1 already has a support (line 33)"},
  // Geometry.
  {"ZeroLength", "zero_length.toml", 28, 9, "members[0].nodes", "member M1 has zero length: nodes 1 and 2 are both at (0, 0, 3.5)"},
  {"OrientationParallel", "orientation_parallel.toml", 31, 15, "members[0].orientation", "orientation (2, 0, 0) is parallel to the axis of member M1"},
  {"DriftZeroHeight", "drift_zero_height.toml", 39, 9, "outputs[0].nodes", "drift height is zero: nodes 1 and 2 are both at z = 0 m"},
  {"DriftUpsideDown", "drift_upside_down.toml", 39, 9, "outputs[0].nodes", "the upper node 1 (z = 0 m) is below the lower node 2 (z = 3.5 m)"},
  {"ReactionUnsupported", "reaction_unsupported.toml", 43, 13, "outputs[0].direction", "no support holds DOF rz and no hinge joins the ground, so this reaction is always zero"},
  // Mass and time step.
  {"NoMembersNoMasses", "no_members.toml", 1, 1, "members", "the model has no members and no point masses, so it has no mass and nothing to integrate"},
  {"NoMembersMasslessNode", "no_members_massless.toml", 11, 6, "nodes[1].id", "node 2 has no mass in its free DOFs ux, uy, uz, rx, ry, rz"},
  {"NoMembersPenaltyStiffness", "no_members_penalty.toml", 5, 16, "model.hinge_method", "hinge_method = \"penalty\" in a model without members needs model.penalty_stiffness and model.penalty_rotational_stiffness for its rigid hinge directions"},
  {"MasslessFreeDof", "massless_dof.toml", 27, 6, "nodes[2].id", "node 3 has no mass in its free DOFs rx, ry, rz"},
  {"DtAboveStable", "dt_unstable.toml", 4, 6, "model.dt", "dt = 0.001 s is above the stable step "},
  // Hinges (DESIGN §7): settings, values, axes, curves, references.
  {"HingeMethodChoice", "hinge_settings.toml", 4, 16, "model.hinge_method", "must be one of \"ntn_exact\", \"ntn_paper\", \"penalty\" (got \"exact\")"},
  {"ClampChoice", "hinge_settings.toml", 5, 9, "model.clamp", "must be one of \"momentum\", \"paper\" (got \"S33\")"},
  {"DampingVelocityChoice", "damping_velocity.toml", 4, 20, "model.damping_velocity", "must be one of \"central\", \"lagged\" (got \"leading\")"},
  {"PenaltyStiffnessPositive", "hinge_settings.toml", 6, 21, "model.penalty_stiffness", "must be positive (got 0)"},
  {"PenaltyRotationalPositive", "hinge_settings.toml", 7, 32, "model.penalty_rotational_stiffness", "must be positive (got -1e+09)"},
  {"LimitStiffnessPositive", "hinge_settings.toml", 8, 19, "model.limit_stiffness", "must be positive (got 0)"},
  {"LimitRotationalNumber", "hinge_settings.toml", 9, 30, "model.limit_rotational_stiffness", "expected a number, got a string"},
  {"ReleasedTwice", "hinge_values.toml", 39, 24, "members[0].release_start[1]", "\"ry\" is released twice"},
  {"ReleaseEmpty", "hinge_values.toml", 40, 15, "members[0].release_end", "expected at least one DOF name to release"},
  {"ReleaseWrongType", "hinge_values.toml", 47, 17, "members[1].release_start", "must be an array of DOF names (released: free) or a table of behaviours per direction, got an integer"},
  {"ReleaseUnknownDirection", "hinge_values.toml", 48, 30, "members[1].release_end.twist", "unknown key 'twist' (this table takes: ux, uy, uz, rx, ry, rz)"},
  {"ReleaseBadDofName", "hinge_values.toml", 55, 18, "members[2].release_start[0]", "must be one of \"ux\", \"uy\", \"uz\", \"rx\", \"ry\", \"rz\" (got \"rw\")"},
  {"BehaviourBadString", "hinge_values.toml", 64, 6, "hinges[0].ux", "must be \"rigid\", \"free\", { linear = k, dashpot = c }, { curve = \"id\" }, { plastic = k, yield = F }, "},
  {"BehaviourWrongType", "hinge_values.toml", 65, 6, "hinges[0].uy", "or { failure = F }, got an integer"},
  {"BehaviourLinearAndCurve", "hinge_values.toml", 66, 32, "hinges[0].uz.curve", "cannot be given together with 'linear'"},
  {"BehaviourDashpotWithCurve", "hinge_values.toml", 67, 31, "hinges[0].rx.dashpot", "only applies with 'linear'"},
  {"BehaviourNegativeLinear", "hinge_values.toml", 68, 17, "hinges[0].ry.linear", "must not be negative (got -1)"},
  {"BehaviourMissingLinear", "hinge_values.toml", 69, 6, "hinges[0].rz.linear", "missing required key 'linear' (or give curve = \"id\")"},
  {"HingeNodeNotGround", "hinge_values.toml", 73, 13, "hinges[1].nodes[1]", "must be a node id or \"ground\" (got \"earth\")"},
  {"BehaviourUnknownKey", "hinge_values.toml", 74, 22, "hinges[1].ux.spring", "unknown key 'spring' (this table takes: linear, dashpot, curve, plastic, "},
  {"HingeNodesCount", "hinge_values.toml", 78, 9, "hinges[2].nodes", "expected [node 1, node 2] (node 2 may be \"ground\"), got 1 value"},
  {"HingeFrameBad", "hinge_values.toml", 79, 9, "hinges[2].frame", "must be \"global\" or { member = \"id\" } (or give axes), got \"local\""},
  {"HingeFrameAndAxes", "hinge_values.toml", 85, 8, "hinges[3].axes", "cannot be given together with 'frame'"},
  {"HingeEccentricType", "hinge_values.toml", 86, 13, "hinges[3].eccentric", "expected a boolean, got a string"},
  {"HingeOutputDirection", "hinge_values.toml", 92, 13, "outputs[0].direction", "must be one of \"ux\", \"uy\", \"uz\", \"rx\", \"ry\", \"rz\" (got \"x\")"},
  {"HingeOutputMissingHinge", "hinge_values.toml", 94, 1, "outputs[1].hinge", "missing required key 'hinge'"},
  {"AxesLeftHanded", "hinge_axes.toml", 59, 8, "hinges[0].axes", "axes must be right-handed (z = x cross y); these have det = -1"},
  {"AxesNotOrthonormal", "hinge_axes.toml", 64, 8, "hinges[1].axes", "axes must be orthonormal to 1e-9 (rows x, y, z of unit length, at right angles): the largest entry of |R R^T - I| is 0.19"},
  {"SupportAxesRows", "hinge_axes.toml", 72, 8, "supports[1].axes", "expected 3 values, got 2"},
  {"SupportAxesNumber", "hinge_axes.toml", 77, 54, "supports[2].axes[2][2]", "expected a number, got a string"},
  {"CurveNotIncreasing", "curve_points.toml", 39, 37, "curves[0].points[2]", "d = 0.001 does not come after the previous point's d = 0.001: deformations must increase strictly"},
  {"CurveOnePoint", "curve_points.toml", 43, 10, "curves[1].points", "expected an array of at least 2 [d, force] points, got 1 point"},
  {"CurveNotArray", "curve_points.toml", 47, 10, "curves[2].points", "expected an array of at least 2 [d, force] points, got an integer"},
  {"CurvePointLength", "curve_points.toml", 51, 23, "curves[3].points[1]", "expected 2 values, got 1"},
  {"DuplicateCurve", "hinge_refs.toml", 57, 6, "curves[1].id", "duplicate curve id 'c1' (first defined at line 53)"},
  {"UnknownCurve", "hinge_refs.toml", 63, 16, "hinges[0].ux.curve", "unknown curve 'nope'"},
  {"HingeUnknownNode", "hinge_refs.toml", 67, 9, "hinges[1].nodes", "unknown node 99"},
  {"HingeUnknownFrameMember", "hinge_refs.toml", 72, 20, "hinges[2].frame.member", "unknown member 'ZZ'"},
  {"DuplicateHinge", "hinge_refs.toml", 75, 6, "hinges[3].id", "duplicate hinge id 'H1' (first defined at line 61)"},
  {"HingeIdIsReleaseName", "hinge_refs.toml", 80, 6, "hinges[4].id", "hinge id 'A.end' is also the name of the member-end release at members[1].release_end: choose another id"},
  {"UnknownHingeOutput", "hinge_refs.toml", 87, 9, "outputs[0].hinge", "unknown hinge 'H9' (hinges are named by their id, <member>.start and <member>.end for releases, support.<node id> for supports with axes)"},
  // Hinge geometry and methods.
  {"HingeNotCoincident", "hinge_geometry.toml", 63, 9, "hinges[0].nodes", "nodes 3 and 2 do not coincide (they are 0.001 m apart): set eccentric = true"},
  {"HingeSameNode", "hinge_geometry.toml", 68, 9, "hinges[1].nodes", "a hinge joins two different nodes; both are node 2"},
  {"HingeGroundEccentric", "hinge_geometry.toml", 73, 13, "hinges[2].eccentric", "a hinge to the ground cannot be eccentric"},
  {"EccentricWithPaper", "hinge_eccentric_paper.toml", 51, 13, "hinges[0].eccentric", "an eccentric hinge (e = (-0.3, 0, 0) m) needs hinge_method = \"ntn_exact\" or \"penalty\": the seed's algorithm (\"ntn_paper\", S 17-37) has no eccentricity"},
  // Rigid cycles: at the hinge that closes them, naming the nodes.
  {"RigidCycleRing", "hinge_cycle.toml", 84, 9, "hinges[2].nodes", "hinge H3 closes a cycle of rigid connections: node 2 - node 3 - node 4 - node 2."},
  {"RigidCycleSupported", "hinge_cycle.toml", 89, 9, "hinges[3].nodes", "hinge H4 closes a cycle of rigid connections: node 1 - ground - node 1."},
  {"RigidCycleSupportAxes", "hinge_cycle.toml", 104, 8, "supports[1].axes", "support with axes support.7 closes a cycle of rigid connections: node 7 - ground - node 7."},
  // Curves against the limit stiffness.
  {"CurveAllRigid", "curve_rigid.toml", 72, 6, "hinges[0].ux", "curve 'stop' has no segment softer than the limit stiffness 1e+12 N/m: all of it is a rigid branch"},
  {"CurveRigidInside", "curve_rigid.toml", 77, 6, "hinges[1].uy", "curve 'middle' has a rigid segment (points 1 to 2, slope at least the limit stiffness 1e+12 N/m) between softer ones"},
  {"CurveStartsOnBranch", "curve_rigid.toml", 78, 6, "hinges[1].uz", "curve 'offset' has its spring part from d = 0.0011 to +inf, which does not contain d = 0"},
  // Effective mass (config/README.md, "Mass and mechanisms").
  {"MasslessSpring", "hinge_massless_spring.toml", 28, 6, "nodes[2].id", "node 3 has no effective mass in rz (global axes), but a hinge spring, dashpot or curve acts there"},
  {"PenaltyMassless", "hinge_penalty_massless.toml", 29, 6, "nodes[2].id", "node 3 has no effective mass in ux, uy, uz, rx, ry, rz (global axes), but a hinge spring, dashpot or curve acts there: an explicit step cannot integrate a massless spring (its frequency is infinite). Give the node a point mass (with inertia for rotations), or make those hinge directions rigid or free. With hinge_method = \"penalty\" a rigid direction is a stiff spring: penalty needs mass on both nodes; give the joint a point mass or use ntn_exact"},
  {"DtAboveHingeStable", "dt_unstable_hinge.toml", 5, 6, "model.dt", "dt = 1e-05 s is above the stable step "},
  // Hinges refused by their method, named by outputs of every hinge kind: the refusals alone
  // (OutputsNamingARefusedHingeAddNoError below).
  {"RefusedOffsetMassNamed", "refused_rigid_plastic_outputs.toml", 39, 10, "point_masses[0].offset", "a point mass on an offset is an eccentric rigid hinge, which needs hinge_method = \"ntn_exact\" or \"penalty\""},
  {"RefusedRigidPlasticNamed", "refused_rigid_plastic_outputs.toml", 44, 6, "hinges[0].ux", "a rigid_plastic direction needs hinge_method = \"ntn_exact\" (exact stick and slip) or \"penalty\""},
  {"RefusedReleaseNamed", "refused_failure_outputs.toml", 34, 22, "members[0].release_end.ry", "a rigid_plastic direction needs hinge_method = \"ntn_exact\""},
  {"RefusedFailureNamed", "refused_failure_outputs.toml", 45, 6, "hinges[1].ux", "a failure direction needs hinge_method = \"ntn_exact\" (exact stick and slip) or \"penalty\""},
  {"RefusedFrictionNamed", "refused_friction_outputs.toml", 38, 6, "hinges[0].ux", "a friction direction needs hinge_method = \"ntn_exact\": under \"penalty\" only a constant limit"},
  {"RefusedFixedIfNamed", "refused_fixed_if_outputs.toml", 38, 6, "hinges[0].ux", "a fixed_if direction with a control needs hinge_method = \"ntn_exact\": under \"penalty\" only a constant limit"},
  // Hostile input: nesting refused before parsing (a dotted key 50 000 deep crashed the parser),
  // the frame rule, and numbers beyond double named at their key.
  {"DeepNesting", "deep_nesting.toml", 6, 62, "", "nested deeper than 32 levels (tables, arrays and inline tables one inside another"},
  {"DtTiny", "dt_tiny.toml", 4, 6, "model.dt", "dt = 1e-300 s gives 1e+297 substeps in the frame period 0.001 s (frame_rate = 1000 Hz), more than the limit 1000000"},
  {"FrameRateRange", "frame_rate_range.toml", 4, 14, "model.frame_rate", "must be between 0.001 and 1e+06 Hz (got 1e-300 Hz)"},
  {"DampingHuge", "damping_huge.toml", 2, 1, "model.dt", "dt = \"auto\" needs 5.55556e+304 substeps in the frame period 0.001 s (frame_rate = 1000 Hz), more than the limit 1000000 (ntn::kMaxSubsteps): the stable step is 2e-308 s, set by member M1"},
  {"HugeE", "numbers_beyond_double.toml", 15, 5, "materials[1].E", "E = 1e+308 Pa gives a non-finite bending stiffness 12 E Iz / (l^3 (1 + Phi)) of member M1"},
  {"SubnormalRho", "numbers_beyond_double.toml", 23, 7, "materials[2].rho", "rho = 1e-310 kg/m^3 is too small: it gives a zero or subnormal end mass rho A l / 2 of member M3"},
  {"HugeA", "numbers_beyond_double.toml", 34, 5, "sections[1].A", "A = 1e+308 m^2 gives a non-finite axial stiffness E A / l of member M2"},
  // Hinge law values at or above the kernel's bound (ntn::kLawValueLimit), at their keys; a roll of more than a turn.
  {"LawRigidPlasticHuge", "law_values_huge.toml", 56, 24, "hinges[0].ux.rigid_plastic", "must be below 1e+300 in magnitude (the kernel's bound on a hinge law's values; got 1e+308)"},
  {"LawHardeningStiffnessHuge", "law_values_huge.toml", 57, 51, "hinges[0].uy.hardening_stiffness", "must be below 1e+300"},
  {"LawYieldHuge", "law_values_huge.toml", 58, 31, "hinges[0].uz.yield", "must be below 1e+300 in magnitude (the kernel's bound on a hinge law's values; got 1e+301)"},
  {"LawFailureHuge", "law_values_huge.toml", 59, 18, "hinges[0].rx.failure", "must be below 1e+300"},
  {"LawFrictionHuge", "law_values_huge.toml", 60, 19, "hinges[0].ry.friction", "must be below 1e+300"},
  {"LawCohesionHuge", "law_values_huge.toml", 61, 35, "hinges[0].rz.cohesion", "must be below 1e+300"},
  {"LawCpHuge", "law_values_huge.toml", 67, 63, "hinges[1].ux.cp", "must be below 1e+300"},
  {"RollHuge", "law_values_huge.toml", 68, 32, "hinges[1].axes.roll", "must be within [-360, 360] degrees, one turn either way (got 1e+308)"},
  // Friction and fixed_if directions whose normal cannot hold them.
  {"FrictionNormalFree", "friction_normals.toml", 55, 33, "hinges[0].ux.normal", "the normal of a friction direction is uz, a free direction: it carries no force, so the limit would be the cohesion alone"},
  {"FixedIfControlFree", "friction_normals.toml", 61, 41, "hinges[1].uy.control", "the control of a fixed_if direction is rx, a free direction: it carries no force, so the direction would never be held"},
  {"FrictionNormalMoment", "friction_normals.toml", 67, 33, "hinges[2].uy.normal", "is ry, a rotation: a translation's friction limit mu N needs a force N, not a moment"},
  {"HingeSpringHuge", "hinge_spring_huge.toml", 54, 6, "hinges[0].ry", "the stable step is zero (set by hinge H1, direction ry (the spring with the largest share of the governing node's bound) (k = 1e+308 N m/rad, dashpot c = 0 N m s/rad)): an intermediate result of the stable-step bound is beyond double there"},
};
// clang-format on

// Names the case in test listings (CTest shows gtest's parameter printout otherwise).
inline void PrintTo(const Expected& c, std::ostream* os) {
  *os << c.test;
}

class ModelError : public ::testing::TestWithParam<Expected> {};

TEST_P(ModelError, ReportedAtItsPlace) {
  const Expected& e = GetParam();
  const auto r = load_model(bad(e.file));
  ASSERT_FALSE(r.ok());
  const auto it = std::find_if(r.errors.begin(), r.errors.end(), [&](const Diagnostic& d) {
    return d.line == e.line && d.column == e.column && d.key == e.key;
  });
  ASSERT_NE(it, r.errors.end()) << "no error at " << e.line << ":" << e.column << " key '" << e.key
                                << "'; got:\n"
                                << ntn::modelc::format_all(r.errors);
  EXPECT_NE(it->message.find(e.fragment), std::string::npos)
      << "message: " << it->message << "\nwanted: " << e.fragment;
  EXPECT_EQ(it->file, bad(e.file));
}

INSTANTIATE_TEST_SUITE_P(BadModels, ModelError, ::testing::ValuesIn(kExpected),
                         [](const ::testing::TestParamInfo<Expected>& p) {
                           return std::string(p.param.test);
                         });

// Every fixture gives exactly the errors listed for it, and every fixture is listed: no
// unexpected extra errors, no fixture left untested.
TEST(ModelErrors, EachFixtureGivesExactlyItsListedErrors) {
  std::map<std::string, int> listed;
  for (const Expected& e : kExpected)
    ++listed[e.file];
  int fixtures = 0;
  for (const auto& entry : std::filesystem::directory_iterator(NTN_MODELC_BAD_DIR)) {
    if (entry.path().extension() != ".toml") continue;
    ++fixtures;
    const std::string name = entry.path().filename().string();
    const auto r = load_model(entry.path().string());
    EXPECT_EQ(static_cast<int>(r.errors.size()), listed[name]) << name << ":\n"
                                                               << ntn::modelc::format_all(r.errors);
  }
  EXPECT_EQ(fixtures, static_cast<int>(listed.size()));
}

// The dt message names the governing member and element and the kernel's stable step: the same
// file with dt = "auto" gives the stable step that the message must quote.
TEST(ModelErrors, DtAboveStableNamesGoverningElementAndStableStep) {
  const auto r = load_model(bad("dt_unstable.toml"));
  ASSERT_EQ(r.errors.size(), 1U);
  std::string text;
  {
    std::FILE* f = std::fopen(bad("dt_unstable.toml").c_str(), "rb");
    ASSERT_NE(f, nullptr);
    char buf[4096];
    std::size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, f)) > 0)
      text.append(buf, n);
    std::fclose(f);
  }
  const auto pos = text.find("dt = 1.0e-3");
  ASSERT_NE(pos, std::string::npos);
  text.replace(pos, 11, "dt = \"auto\"");
  const auto ok = ntn::modelc::load_model_from_string(text, "auto.toml");
  ASSERT_TRUE(ok.ok()) << ntn::modelc::format_all(ok.errors);
  char stable[64];
  std::snprintf(stable, sizeof stable, "%.6g s", ok.model->stable.dt_stable);
  const std::string& msg = r.errors[0].message;
  EXPECT_NE(msg.find(std::string("above the stable step ") + stable), std::string::npos) << msg;
  // C1 (2 m, 4 elements of 0.5 m) governs over M1 (one 1 m element); its elements are equal, so
  // the first of them is reported.
  const int gov = ok.model->stable.governing_element;
  EXPECT_EQ(ok.model
                ->members[static_cast<std::size_t>(
                    ok.model->element_member[static_cast<std::size_t>(gov)])]
                .name,
            "C1");
  EXPECT_NE(msg.find("set by member C1, element 1 of 4 (model element 1)"), std::string::npos)
      << msg;
}

// A stiff rotational spring between two 1 m members governs the stable step. By DESIGN §6 the
// spring alone is a two-node oscillator with omega^2 = k (1/m1 + 1/m2), here both m = rho A l^3
// / 78 (the HRZ bending inertia of an element end about local z = global z, no rotary inertia);
// the kernel's strict bound (kernel/README.md "Stable time step") adds, at each member end, the
// element's own omega_e^2 (each end has one element and no other mass), so with no damping
// dt = 2 / sqrt(omega^2 + Omega^2), Omega = 2 / dt_elements (the same file with dt = "auto").
// The message must quote that step (%.6g: 1e-5 relative), never above the spring's own 2 / omega,
// and name the hinge and direction.
TEST(ModelErrors, DtAboveStableNamesGoverningHinge) {
  const auto r = load_model(bad("dt_unstable_hinge.toml"));
  ASSERT_EQ(r.errors.size(), 1U);
  std::string text;
  {
    std::FILE* f = std::fopen(bad("dt_unstable_hinge.toml").c_str(), "rb");
    ASSERT_NE(f, nullptr);
    char buf[4096];
    std::size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, f)) > 0)
      text.append(buf, n);
    std::fclose(f);
  }
  const auto pos = text.find("dt = 1.0e-5");
  ASSERT_NE(pos, std::string::npos);
  text.replace(pos, 11, "dt = \"auto\"");
  const auto ok = ntn::modelc::load_model_from_string(text, "auto.toml");
  ASSERT_TRUE(ok.ok()) << ntn::modelc::format_all(ok.errors);
  const double m = 7850.0 * 1.0e-2 * 1.0 / 78.0;  // kg m^2: rho A l^3 / 78, l = 1 m
  const double omega2 = 1.0e12 * (1.0 / m + 1.0 / m);
  const double elements = 2.0 / ok.model->stable.dt_elements;
  const double expected = 2.0 / std::sqrt(omega2 + elements * elements);
  const std::string& msg = r.errors[0].message;
  const std::string at = "above the stable step ";
  const std::size_t p = msg.find(at);
  ASSERT_NE(p, std::string::npos) << msg;
  const double quoted = std::strtod(msg.c_str() + p + at.size(), nullptr);
  EXPECT_NEAR(quoted / expected, 1.0, 1e-5) << msg;
  EXPECT_LE(quoted, 2.0 / std::sqrt(omega2) * (1 + 1e-5)) << msg;
  EXPECT_NE(msg.find(" s set by hinge H1, direction rz (the spring with the largest share"),
            std::string::npos)
      << msg;
}

// Outputs that name a refused hinge add no error and read no hinge: each of these models (a
// rigid_plastic or rigid failure direction under ntn_paper, a friction or fixed_if direction with
// a control under penalty, a refused member-end release and point mass on an offset, next to a
// hinge that is built) gives exactly the errors of its text without the [[outputs]] tables, which
// end each file: a hinge's name leads to a hinge that was built, or to none.
TEST(ModelErrors, OutputsNamingARefusedHingeAddNoError) {
  for (const char* name : {"refused_rigid_plastic_outputs.toml", "refused_failure_outputs.toml",
                           "refused_friction_outputs.toml", "refused_fixed_if_outputs.toml"}) {
    std::string text;
    {
      std::FILE* f = std::fopen(bad(name).c_str(), "rb");
      ASSERT_NE(f, nullptr) << name;
      char buf[4096];
      std::size_t n;
      while ((n = std::fread(buf, 1, sizeof buf, f)) > 0)
        text.append(buf, n);
      std::fclose(f);
    }
    const std::size_t outputs = text.find("\n[[outputs]]");
    ASSERT_NE(outputs, std::string::npos) << name;
    const auto with = ntn::modelc::load_model_from_string(text, name);
    const auto without = ntn::modelc::load_model_from_string(text.substr(0, outputs + 1), name);
    ASSERT_FALSE(without.errors.empty()) << name;
    EXPECT_EQ(ntn::modelc::format_all(with.errors), ntn::modelc::format_all(without.errors))
        << name;
  }
}

TEST(ModelErrors, MissingFile) {
  const auto r = load_model(bad("no_such_file.toml"));
  ASSERT_EQ(r.errors.size(), 1U);
  EXPECT_EQ(r.errors[0].line, 1);
  EXPECT_EQ(r.errors[0].column, 1);
  EXPECT_EQ(r.errors[0].message,
            "cannot read the model file: no such file (or a path through a file that is not a "
            "directory)");
  EXPECT_TRUE(r.unreadable);  // the programs exit 2: a usage error, not a model's
}

TEST(ModelErrors, DiagnosticFormat) {
  const Diagnostic d{"m.toml", 7, 5, "materials[0].E", "must be positive (got 0)"};
  EXPECT_EQ(d.format(), "m.toml:7:5: error: key 'materials[0].E': must be positive (got 0)");
  const Diagnostic s{"m.toml", 5, 2, "", "TOML syntax: x"};
  EXPECT_EQ(s.format(), "m.toml:5:2: error: TOML syntax: x");
}

// Errors come sorted by position, whatever order the tables were read in.
TEST(ModelErrors, SortedByPosition) {
  const auto r = load_model(bad("unknown_key.toml"));
  ASSERT_GT(r.errors.size(), 2U);
  EXPECT_TRUE(std::is_sorted(r.errors.begin(), r.errors.end(), [](const auto& a, const auto& b) {
    return a.line != b.line ? a.line < b.line : a.column < b.column;
  }));
}

}  // namespace modelc_errors_test
