// Numeric constants shared by host and shaders.
#ifndef MIXTRACE_SHARED_CONSTANTS_H
#define MIXTRACE_SHARED_CONSTANTS_H
#include "shared/dialect.h"
SHARED_BEGIN

const float kPi = 3.14159265358979323846f;
const float kInvPi = 0.31830988618379067154f;
const float kTwoPi = 6.28318530717958647692f;
const float kFloatMax = 3.402823466e+38f;

// GGX alpha is clamped from below: alpha = 0 is a delta distribution the estimators here do not
// treat specially, and near-mirror (alpha 0.002) already spans the dynamic range of float pdfs.
const float kMinAlpha = 0.002f;

// glTF's default index of refraction (KHR_materials_ior), whose F0 is the core specification's 0.04.
const float kDefaultIor = 1.5f;
// A volumetric glass's IOR is kept at least this far above 1: at exactly 1 the rough refraction
// collapses to a delta (wi = -wo) that no density describes.
const float kMinVolumeIor = 1.01f;

SHARED_END
#endif
