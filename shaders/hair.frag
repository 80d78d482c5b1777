#version 450
#extension GL_GOOGLE_include_directive : require
// Marschner-shaded hair ribbons, premultiplied alpha (see render/passes/hair_pass.hpp).
#include "hair_shading.glsl"
#include "hair_uniforms.glsl"

layout(set = 0, binding = 3) uniform sampler2D longitudinalLut;
layout(set = 0, binding = 4) uniform sampler2DArray azimuthalLut;

layout(location = 0) in vec3 inWorldPosition;
layout(location = 1) in vec3 inTangent;
layout(location = 2) in float inCoverage;
layout(location = 0) out vec4 outColor;

void main() {
  float tangentLength = length(inTangent);
  vec3 tangent = tangentLength > 1e-6 ? inTangent / tangentLength : vec3(0.0);
  vec3 toEye = hairToEye(inWorldPosition);
  vec3 radiance = hair.ambient.rgb;
  for (uint i = 0u; i < hair.counts.x; ++i)
    radiance += hairScattering(longitudinalLut, azimuthalLut, hair.lightDirection[i].xyz, toEye, tangent) *
                hair.lightRadiance[i].rgb;
  float alpha = hair.groom.z * clamp(inCoverage, 0.0, 1.0);
  outColor = vec4(radiance * alpha, alpha);
}
