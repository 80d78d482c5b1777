#version 450
#extension GL_GOOGLE_include_directive : require
#define HAIR_OCCLUSION_SAMPLES 1
#include "hair_occlusion.glsl"
