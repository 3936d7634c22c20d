// Included by the Highway sources (element_pass.cpp, dof_pass.cpp) before any Highway header.
// Highway 1.0.3 (Debian 12's libhwy-dev) makes AVX3_DL a dispatch target only when asked
// (HWY_WANT_AVX3_DL) or when it is the compile-time baseline, and its test of the baseline reads
// a macro it never defines, so a build whose flags make AVX3_DL the baseline (-march=native on
// a Zen 5, or Ice Lake and later: VBMI2, BITALG and AVX-VNNI) stops with "Logic error: best
// baseline should be included in dynamic targets". Such a build asks for AVX3_DL here, which is
// what Highway means to do: the target list of every other build is unchanged.
#pragma once

#if !defined(HWY_WANT_AVX3_DL) && defined(__AVX512VBMI2__) && defined(__AVX512BITALG__) && \
    defined(__AVXVNNI__)
#define HWY_WANT_AVX3_DL
#endif
