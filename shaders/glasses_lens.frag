#version 450
#extension GL_GOOGLE_include_directive : require
// glasses_refraction.glsl over a single-sample depth image.
#include "glasses_refraction.glsl"
