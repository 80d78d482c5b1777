// Marschner hair shading from the two lookup tables that MarschnerLut bakes
// (render/luts/marschner_lut.hpp; the model is render/luts/marschner.hpp, eq. (1)).
//
//   longitudinal table (sampler2D, RGBA16F):  texel parameter x = (θi/π + ½, θr/π + ½)
//                                              rgb = (M_R, M_TT, M_TRT), a unused
//   azimuthal table (sampler2DArray, RGBA32F): texel parameter x = (φ/π, cos θr)
//                                              layer 0 = (N_TT.rgb, N_R), layer 1 = (N_TRT.rgb, unused)
//
// Texel centre i of a table of n texels sits at parameter x = i/(n − 1): both ends of each
// range land on texel centres, so bilinear filtering interpolates between exact samples and
// never extrapolates past ±π/2, 0 or π.
//
// Include after `#extension GL_GOOGLE_include_directive : require`.

const float kHairPi = 3.14159265358979;

// Normalised texture coordinates of the parameter x ∈ [0, 1]² in a table of `size` texels.
vec2 hairLutCoordinates(vec2 x, vec2 size) {
  return (0.5 + x * (size - 1.0)) / size;
}

// The parameter x ∈ [0, 1]² of texel `texel` in a table of `size` texels (the inverse map).
vec2 hairLutParameter(uvec2 texel, uvec2 size) {
  return vec2(texel) / vec2(size - 1u);
}

// S(ωi, ωr) per RGB (1/sr): the radiance scattered towards the eye per unit irradiance from the
// light, measured perpendicular to the light direction. A directional light of perpendicular
// irradiance E adds S·E: no cosine factor, it is inside M (d'Eon et al. 2011 normalisation).
// toLight, toEye and tangent (root → tip) are unit vectors in one space. Three fetches: M, and
// the two layers of N at the same coordinates. `spread` (radians ≥ 0) is how far the tangent
// turns over the piece of strand this evaluation stands for: the lookups read the mip level
// whose texels span that angle, so a strand that curls within a shading sample gets the
// filtered lobe rather than an aliased peak (the tables are mip-mapped for this, as in Nalu).
// asin and acos may be approximations of ~1e-4 rad (lavapipe); that moves a lookup by < 0.05
// texel. `bodyColour` multiplies the two lobes that cross the fibre (TT, TRT), not its surface
// reflection (R): a strand's own colour (render/hair_data.hpp, HairStrandLook), 1 for the
// preset's.
vec3 hairScattering(sampler2D longitudinalLut, sampler2DArray azimuthalLut, vec3 toLight, vec3 toEye, vec3 tangent,
                    float spread, vec3 bodyColour) {
  float sinThetaI = clamp(dot(toLight, tangent), -1.0, 1.0);
  float sinThetaR = clamp(dot(toEye, tangent), -1.0, 1.0);
  vec2 theta = asin(vec2(sinThetaI, sinThetaR));
  // φ: angle between the projections on the normal plane (GPU Gems 2 ch. 23 computes cos φ the same way).
  vec3 lightPerp = toLight - sinThetaI * tangent;
  vec3 eyePerp = toEye - sinThetaR * tangent;
  float norms = dot(lightPerp, lightPerp) * dot(eyePerp, eyePerp);
  float cosPhi = norms > 1e-12 ? clamp(dot(lightPerp, eyePerp) * inversesqrt(norms), -1.0, 1.0) : 1.0;
  float cosThetaR = sqrt(max(1.0 - sinThetaR * sinThetaR, 0.0));

  vec2 mSize = vec2(textureSize(longitudinalLut, 0));
  vec2 nSize = vec2(textureSize(azimuthalLut, 0).xy);
  // Texels per radian along the θ axis of M (π rad across) and the φ axis of N (π rad across).
  float mLod = log2(max(spread / kHairPi * (mSize.x - 1.0), 1.0));
  float nLod = log2(max(spread / kHairPi * (nSize.x - 1.0), 1.0));
  vec4 m = textureLod(longitudinalLut, hairLutCoordinates(theta / kHairPi + 0.5, mSize), mLod);
  vec2 n = hairLutCoordinates(vec2(acos(cosPhi) / kHairPi, cosThetaR), nSize);
  vec4 nTTR = textureLod(azimuthalLut, vec3(n, 0.0), nLod);
  vec4 nTRT = textureLod(azimuthalLut, vec3(n, 1.0), nLod);
  return m.r * nTTR.a + m.g * nTTR.rgb * bodyColour + m.b * nTRT.rgb * bodyColour;
}
