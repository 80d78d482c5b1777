// Tangent frame from screen-space derivatives of position and uv, so meshes need no stored
// tangents (Schüler, "Normal Mapping Without Precomputed Tangents", 2013, after ShaderX5), shared
// so that normal maps mean the same thing in every pass that reads them. Works in any raster: the
// camera's or texture space's. The axes are the uv gradients, scaled together: where uv stretches
// unequally along u and v they are not of unit length (the map's x and y are scaled by the
// gradients' ratio).
mat3 cotangentFrame(vec3 normal, vec3 position, vec2 uv) {
  vec3 dp1 = dFdx(position);
  vec3 dp2 = dFdy(position);
  vec2 duv1 = dFdx(uv);
  vec2 duv2 = dFdy(uv);
  vec3 dp2perp = cross(dp2, normal);
  vec3 dp1perp = cross(normal, dp1);
  vec3 tangent = dp2perp * duv1.x + dp1perp * duv2.x;
  vec3 bitangent = dp2perp * duv1.y + dp1perp * duv2.y;
  // The exact gradients divide by det = dp1·dp2perp; only its sign matters once we normalise.
  // It is negative under Vulkan's downward framebuffer Y, so it cannot be dropped.
  float det = dot(dp1, dp2perp);
  float scale = (det < 0.0 ? -1.0 : 1.0) *
                inversesqrt(max(max(dot(tangent, tangent), dot(bitangent, bitangent)), 1e-20));
  return mat3(tangent * scale, bitangent * scale, normal);
}
