// Pre-integrated skin from the table that PreintegratedSkinLut bakes
// (render/luts/preintegrated_skin_lut.hpp; the maths is render/luts/preintegrated_skin.hpp and
// render/luts/skin_specular.hpp).
//
//   one R16F sampler2DArray, texel centre i of n at parameter s = i/(n − 1), likewise t:
//   layers 0–2 = pre-integrated diffuse D per R, G, B at N·L = 2s − 1, 1/r = t · maxCurvature (1/mm)
//   layer 3    = 0.5 · Beckmann(N·H = s, α = t)^0.1 (decode: pow(2a, 10))
//
// Include after `#extension GL_GOOGLE_include_directive : require`.

const float kSkinPi = 3.14159265358979;
/// F0 of skin's surface layer (d'Eon & Luebke, GPU Gems 3 ch. 14, Example 14-2).
const float kSkinSpecularF0 = 0.028;

// The parameter (s, t) ∈ [0, 1]² of texel `texel` in a table of size × size texels.
vec2 skinLutParameter(uvec2 texel, uint size) {
  return vec2(texel) / float(size - 1u);
}

// Normalised texture coordinates of the parameter x ∈ [0, 1]² in a table of `size` texels.
vec2 skinLutCoordinates(vec2 x, float size) {
  return (0.5 + clamp(x, 0.0, 1.0) * (size - 1.0)) / size;
}

// Diffuse light per unit irradiance of colour channel `channel` (0–2: R, G, B) for a light at
// N·L on skin of curvature `curvature` (1/r in 1/mm: a mesh's 1/r in world units divided by
// millimetres per unit). It replaces max(N·L, 0) of Lambert; curvatures past the table's
// maxCurvature read its last row.
float preintegratedSkinDiffuse(sampler2DArray lut, int channel, float nDotL, float curvature, float maxCurvature) {
  float size = float(textureSize(lut, 0).x);
  vec2 x = vec2(0.5 * nDotL + 0.5, curvature / maxCurvature);
  return textureLod(lut, vec3(skinLutCoordinates(x, size), float(channel)), 0.0).r;
}

// Beckmann's normalised distribution (1/sr) at N·H for roughness α ∈ (0, 1], from the table.
float preintegratedSkinBeckmann(sampler2DArray lut, float nDotH, float roughness) {
  float size = float(textureSize(lut, 0).x);
  float encoded = textureLod(lut, vec3(skinLutCoordinates(vec2(nDotH, roughness), size), 3.0), 0.0).r;
  return pow(2.0 * encoded, 10.0);
}

// Schlick's Fresnel for the cosine between a direction and the microfacet normal.
float skinSchlickFresnel(float cosTheta, float f0) {
  float c = 1.0 - clamp(cosTheta, 0.0, 1.0);
  float c2 = c * c;
  return f0 + (1.0 - f0) * c2 * c2 * c;
}

// Kelemen/Szirmay-Kalos specular, 1/sr: ρs · D(N·H) · F(H·V) / |L + V|²; multiply by N·L and the
// light's irradiance. Unit vectors in one space; ρs as in render/luts/skin_specular.hpp (π times
// GPU Gems 3's, whose Beckmann term leaves out 1/π).
float kelemenSzirmayKalos(sampler2DArray lut, vec3 normal, vec3 toLight, vec3 toEye, float roughness, float rhoS) {
  if (dot(normal, toLight) <= 0.0 || dot(normal, toEye) <= 0.0) return 0.0;
  vec3 h = toLight + toEye;
  float h2 = dot(h, h);
  if (h2 <= 1e-12) return 0.0;
  vec3 halfway = h * inversesqrt(h2);
  float d = preintegratedSkinBeckmann(lut, max(dot(normal, halfway), 0.0), roughness);
  return rhoS * d * skinSchlickFresnel(dot(halfway, toEye), kSkinSpecularF0) / h2;
}
