#version 450
#extension GL_GOOGLE_include_directive : require
// hair_occlusion.glsl over the 4 samples of a multisampled depth image.
#define HAIR_OCCLUSION_SAMPLES 4
#include "hair_occlusion.glsl"
