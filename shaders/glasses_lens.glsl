// A spectacle lens (render/lens.hpp): its constants and the geometry of its two surfaces, in the
// lens frame (metres; the axis along z, the front vertex at 0, the back vertex at −thickness, +z
// out of the front surface). Mirrors GlassesPass's LensConstants (render/passes/glasses_pass.cpp).

layout(push_constant) uniform LensConstants {
  mat4 model;          // lens frame → world, rigid
  vec4 surfaces;       // x: front curvature, y: back curvature (1/m); z: centre thickness (m); w: ior
  vec4 outline;        // xy: half aperture (m)
  vec4 transmittance;  // rgb
} lens;

const float kPi = 3.14159265358979;

// How far a surface of curvature c falls back from its vertex at squared distance r2 from the axis.
float lensSag(float c, float r2) {
  return c * r2 / (1.0 + sqrt(max(1.0 - c * c * r2, 0.0)));
}

// Where the ray o + s·d (d unit) meets the surface of curvature c whose vertex is at z = vertexZ:
// the sphere c·|q|² + 2·q.z = 0 in q = p − (0, 0, vertexZ), which is the plane q.z = 0 for c = 0.
// The root on the vertex's side of the sphere; −1 where the ray misses it.
float lensSurfaceHit(vec3 o, vec3 d, float c, float vertexZ) {
  vec3 q = o - vec3(0.0, 0.0, vertexZ);
  float b = c * dot(q, d) + d.z;
  float cc = c * dot(q, q) + 2.0 * q.z;
  float discriminant = b * b - c * cc;
  if (discriminant < 0.0) return -1.0;
  // −cc / (b ± √disc), the sign that does not cancel: finite as c → 0, where it is −cc / 2b.
  float denominator = b + (b >= 0.0 ? 1.0 : -1.0) * sqrt(discriminant);
  return denominator != 0.0 ? -cc / denominator : -1.0;
}

// The unit normal, towards +z, of the surface of curvature c with its vertex at z = vertexZ, at p on it.
vec3 lensSurfaceNormal(vec3 p, float c, float vertexZ) {
  return normalize(vec3(c * p.xy, c * (p.z - vertexZ) + 1.0));
}
