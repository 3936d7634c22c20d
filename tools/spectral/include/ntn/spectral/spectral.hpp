// Everything of ntn::spectral (tools/spectral/README.md).
#pragma once

#include "ntn/spectral/amplitude.hpp"
#include "ntn/spectral/channels.hpp"
#include "ntn/spectral/error.hpp"
#include "ntn/spectral/fdd.hpp"
#include "ntn/spectral/fft.hpp"
#include "ntn/spectral/frf.hpp"
#include "ntn/spectral/peaks.hpp"
#include "ntn/spectral/reference.hpp"
#include "ntn/spectral/spectrum.hpp"
#include "ntn/spectral/welch.hpp"
#include "ntn/spectral/window.hpp"
