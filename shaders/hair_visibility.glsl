// What the hair leaves of the environment's light at a point (render/passes/hair_density_pass.hpp):
// HAIR_VISIBILITY_SET and HAIR_VISIBILITY_BINDING name the occlusion volume's binding; the
// placement (HairVisibilityPlacement) comes from the includer's uniforms.
//
//   #define HAIR_VISIBILITY_SET <set> and HAIR_VISIBILITY_BINDING <binding>
//   #include "hair_visibility.glsl"

layout(set = HAIR_VISIBILITY_SET, binding = HAIR_VISIBILITY_BINDING) uniform sampler3D hairOcclusion;

// The occlusion (−b, 1 − a) at `position` (metres): 0 outside the grid and where it is off. The
// test spares the lookup where a whole block of pixels lies outside, as most of a frame does.
vec4 hairOcclusionAt(vec4 origin, vec4 scale, vec3 position) {
  vec3 uvw = (position - origin.xyz) * scale.xyz;
  if (scale.w == 0.0 || any(lessThan(uvw, vec3(0.0))) || any(greaterThan(uvw, vec3(1.0)))) return vec4(0.0);
  return texture(hairOcclusion, uvw);
}

// The share of a surface's diffuse environment light facing `normal`: a + ⅔ b·n, the clamped
// cosine's average of V(ω) = a + b·ω.
float hairSurfaceVisibility(vec4 origin, vec4 scale, vec3 position, vec3 normal) {
  vec4 occlusion = hairOcclusionAt(origin, scale, position);
  return clamp(1.0 - occlusion.w - (2.0 / 3.0) * dot(occlusion.xyz, normal), 0.0, 1.0);
}

// The share of a fibre's: a, the average over every direction, as the lobes scatter all round.
float hairFibreVisibility(vec4 origin, vec4 scale, vec3 position) {
  return clamp(1.0 - hairOcclusionAt(origin, scale, position).w, 0.0, 1.0);
}
