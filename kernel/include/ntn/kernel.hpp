// ntn-rt kernel: include this one header.
#pragma once

#include "ntn/beam.hpp"
#include "ntn/clamp.hpp"
#include "ntn/constraint_forest.hpp"
#include "ntn/hinge.hpp"
#include "ntn/hinge_methods.hpp"
#include "ntn/integrator.hpp"
#include "ntn/loads.hpp"
#include "ntn/model.hpp"
#include "ntn/model_spec.hpp"
#include "ntn/ntn_exact.hpp"
#include "ntn/ntn_paper.hpp"
#include "ntn/penalty.hpp"
#include "ntn/residual.hpp"
#include "ntn/state.hpp"
#include "ntn/status.hpp"
#include "ntn/time_step.hpp"
