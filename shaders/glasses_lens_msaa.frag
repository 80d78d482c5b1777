#version 450
#extension GL_GOOGLE_include_directive : require
// glasses_refraction.glsl over a multisampled depth image (its first sample).
#define GLASSES_MULTISAMPLED_DEPTH
#include "glasses_refraction.glsl"
