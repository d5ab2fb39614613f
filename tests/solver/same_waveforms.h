// Bit-for-bit comparison of two simulations' results: every component's
// samples (times, values, rates and the explicit pair's bubble terms).
#pragma once

#include <gtest/gtest.h>

#include <cstring>

#include "core/solver/simulation.h"

namespace asgard::testing {

inline void ExpectSameWaveforms(const solver::Simulation& a, const solver::Simulation& b) {
  ASSERT_EQ(a.component_count(), b.component_count());
  for (int c = 0; c < a.component_count(); ++c) {
    const auto& wa = a.component(c).waveform();
    const auto& wb = b.component(c).waveform();
    ASSERT_EQ(wa.size(), wb.size()) << "component " << c;
    const size_t bytes = static_cast<size_t>(wa.variable_count()) * sizeof(double);
    for (int k = 0; k < wa.size(); ++k) {
      ASSERT_EQ(wa.time(k), wb.time(k)) << "component " << c << " sample " << k;
      ASSERT_EQ(std::memcmp(wa.x(k), wb.x(k), bytes), 0) << "component " << c << " sample " << k;
      ASSERT_EQ(std::memcmp(wa.f(k), wb.f(k), bytes), 0) << "component " << c << " sample " << k;
      ASSERT_EQ(std::memcmp(wa.bubble(k), wb.bubble(k), bytes), 0)
          << "component " << c << " sample " << k;
    }
  }
}

}  // namespace asgard::testing
