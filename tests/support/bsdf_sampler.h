#pragma once
// bsdfSample (shaders/shared/bsdf.h) as a chi2::DirectionSampler, for the chi-square tests of the
// BRDF and of glass: each draw takes (u, u, uLobe) in that order, and a draw whose reported pdf is
// not the density of a successful sample (finite and positive), or not 0 for a failed one, fails
// the calling test.
#include <cmath>

#include <gtest/gtest.h>

#include "shared/bsdf.h"
#include "support/chi2.h"

namespace mixtrace::testing {

inline chi2::DirectionSampler bsdfSampler(const shared::BsdfParams& m, const glm::vec3& wo) {
  return [m, wo](chi2::Uniforms& u, glm::vec3& wi) {
    const glm::vec2 uDir = u.next2();
    const float uLobe = u.next();
    float pdf = -1.0f;
    const bool ok = shared::bsdfSample(m, wo, uDir, uLobe, wi, pdf);
    if (ok && !(pdf > 0.0f && std::isfinite(pdf))) ADD_FAILURE() << "sampled pdf " << pdf;
    if (!ok && pdf != 0.0f) ADD_FAILURE() << "failed sample with pdf " << pdf;
    return ok;
  };
}

}  // namespace mixtrace::testing
