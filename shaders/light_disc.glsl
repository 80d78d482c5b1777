// Push constants of shaders/light_disc.vert and .frag (LightDiscConstants in
// render/passes/light_disc_pass.cpp).
layout(push_constant) uniform Disc {
  // NDC → a direction from the eye: the inverse of projection × the view's rotation.
  mat4 ndcToDirection;
  vec4 bounds;       // NDC rectangle: min xy, max xy
  vec4 towardLight;  // xyz: unit direction towards the light; w: the disc's angular radius, radians
  vec4 radiance;     // rgb: linear radiance inside the disc
} disc;
