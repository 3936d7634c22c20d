// `ntn-model modes`: a loaded model's modes with its hinges applied exactly, as text and as JSON
// (tools/modelc/README.md, "ntn-model modes", gives the JSON schema). The modes, effective masses
// and the hinge linearization are ntn::modal's (tools/modal); this file only arranges them.
// Library target ntn_model_modes (links ntn::modelc and ntn::modal).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "ntn/modal/modal.hpp"
#include "ntn/modelc/model_description.hpp"

namespace ntn::modelc {

// The JSON's "schema" value; a change of the JSON's keys or meanings changes the number.
inline constexpr const char* kModesSchema = "ntn-model-modes/2";

// How the modal analysis treated a hinge direction (hinge axes), from ntn::modal::linearize_hinges.
enum class HingeTreatment : std::uint8_t {
  kTied,    // tied exactly (rigid, or a curve whose origin lies on a rigid branch)
  kSpring,  // a linear spring (linear, or a curve's slope at the origin)
  kFree,    // no stiffness (free, linear with k = 0, or a curve with a negative slope there)
};
const char* to_string(HingeTreatment t);

struct HingeDirections {
  std::string name;         // the model file's name: "H1", "B1.start", "support.3"
  std::string description;  // ModelDescription::describe_hinge
  std::array<HingeTreatment, 6> treatment{};
  std::array<double, 6> stiffness{};  // kSpring: N/m (ux, uy, uz), N m/rad (rx, ry, rz)
};

struct ModesReport {
  std::string model_name;
  std::string model_file;
  int requested = 0;           // -n
  double alpha = 0, beta = 0;  // the model's damping C = alpha M + beta K_el (1/s, s)
  modal::ModalResult result;   // result.modes() <= requested (fewer when the model has fewer)
  std::vector<HingeDirections> hinges;       // one per model hinge, in the model's order
  std::vector<std::string> mechanism_nodes;  // describe_node of each result.mechanisms entry
};

// Loads nothing: the model is already validated (load_model). The `requested` lowest modes
// (ntn::modal::modal_analysis with supports and rigid hinge directions tied exactly). A failed
// analysis leaves result.error set.
ModesReport modes_report(const ModelDescription& model, int requested);

// The text `ntn-model modes` prints: ntn::modal::mode_table (mode, Hz, period, damping, effective
// mass % in x, y, z and cumulative), then the hinges' directions and the mechanisms.
std::string modes_text(const ModesReport& report);

// The same as one JSON object (schema kModesSchema). Numbers are printed with 17 significant
// digits (they read back as the same doubles); an infinite period (a rigid-body mode) is null.
std::string modes_json(const ModesReport& report);

}  // namespace ntn::modelc
