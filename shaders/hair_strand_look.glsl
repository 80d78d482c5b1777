// A dense strand's look (render/strand_looks.hpp): factors of its groom's settings, two RGBA32F
// texels per strand, read as a texel buffer (lavapipe gathers a texel fetch's lanes at once where
// it loads a storage buffer lane by lane). Declare `samplerBuffer hairStrandLooks` before
// including this file.

// x: width factor, y: tip width factor, z: opacity factor (w unused).
vec4 hairStrandShape(uint strand) {
  return texelFetch(hairStrandLooks, int(2u * strand));
}

// What multiplies the light that crosses the fibre (TT, TRT and the ambient term).
vec3 hairStrandColour(uint strand) {
  return texelFetch(hairStrandLooks, int(2u * strand + 1u)).rgb;
}
