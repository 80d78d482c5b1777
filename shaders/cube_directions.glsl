// The major-axis table of Vulkan's cube face selection, inverted (as cubeDirection in
// render/environment/environment_map.cpp): the unit direction through (s, t) ∈ [0, 1]² of `face`.
vec3 cubeDirection(uint face, vec2 st) {
  float a = 2.0 * st.x - 1.0, b = 2.0 * st.y - 1.0;
  vec3 d;
  if (face == 0u) d = vec3(1.0, -b, -a);
  else if (face == 1u) d = vec3(-1.0, -b, a);
  else if (face == 2u) d = vec3(a, 1.0, b);
  else if (face == 3u) d = vec3(a, -1.0, -b);
  else if (face == 4u) d = vec3(a, -b, 1.0);
  else d = vec3(-a, -b, -1.0);
  return normalize(d);
}
