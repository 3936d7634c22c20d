// Status codes: the kernel reports problems, it never throws (STYLE: counted and flagged).
#pragma once

#include <cstdint>

namespace ntn {

enum class InitError : std::uint8_t {
  kNone,
  kBadReference,         // a node, time function or element index out of range
  kBadProperty,          // non-positive E, G, rho, A, I or J
  kZeroLength,           // element nodes coincide
  kOrientation,          // orientation vector parallel to the element axis
  kMassless,             // a free DOF with no mass (`where` = global DOF index)
  kBadTimeStep,          // dt not positive
  kTimeStepAboveStable,  // dt above the stable step (`where` = governing element)
  kBadInput,             // an input channel names a bad node, DOF or range (`where` = channel)
  kBadOutput,            // an output channel names a bad node, DOF or element (`where` = channel)
  kBadTimeFunction,      // a time function's points out of range or not increasing
  kBadHinge,             // a hinge with a bad node, frame, curve or stiffness (`where` = hinge)
  kRigidCycle,           // rigid hinge directions form a cycle (`where` = the closing hinge)
  kMechanism,            // an effective mass that cannot be inverted (`where` = hinge or node)
  kStorageSizes,         // run-time storage bound for other sizes, or a model with no node
  kCorotationalHinge,    // a hinge that turns with its nodes holds what cannot turn yet
                         // (turning_hinge_check; `where` = hinge)
};

struct [[nodiscard]] InitStatus {
  InitError error = InitError::kNone;
  int where = -1;  // element, DOF or -1, as the error says
  constexpr bool ok() const { return error == InitError::kNone; }
};

constexpr const char* to_string(InitError e) {
  switch (e) {
    case InitError::kNone:
      return "ok";
    case InitError::kBadReference:
      return "reference out of range";
    case InitError::kBadProperty:
      return "non-positive material or section property";
    case InitError::kZeroLength:
      return "zero-length element";
    case InitError::kOrientation:
      return "orientation vector parallel to the element axis";
    case InitError::kMassless:
      return "free DOF without mass";
    case InitError::kBadTimeStep:
      return "time step not positive";
    case InitError::kTimeStepAboveStable:
      return "time step above the stable step";
    case InitError::kBadInput:
      return "input channel with a bad node, DOF or range";
    case InitError::kBadOutput:
      return "output channel with a bad node, DOF or element";
    case InitError::kBadTimeFunction:
      return "time function points out of range or not increasing";
    case InitError::kBadHinge:
      return "hinge with a bad node, frame, curve or stiffness";
    case InitError::kRigidCycle:
      return "rigid hinge directions form a cycle";
    case InitError::kMechanism:
      return "effective mass of a rigid tree cannot be inverted";
    case InitError::kStorageSizes:
      return "storage bound for other sizes, or a model without nodes";
    case InitError::kCorotationalHinge:
      return "hinge at a corotational element holds a direction whose rows cannot turn";
  }
  return "unknown";
}

enum class StepStatus : std::uint8_t {
  kOk,
  kInputHeld,  // a non-finite or out-of-range input was replaced by its last good value
  kDiverged,   // a velocity became non-finite: the state is no longer meaningful
};

// Fault bits kept in State::faults (sticky until the caller clears them).
enum Fault : std::uint32_t {
  kFaultInputHeld = 1U << 0,
  kFaultDiverged = 1U << 1,
  kFaultInputRange = 1U << 2,
  // an element's axial force or chord rotation beyond the stable step's bound (geometry.hpp)
  kFaultGeometryBound = 1U << 3,
};

}  // namespace ntn
