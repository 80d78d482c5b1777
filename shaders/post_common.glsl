// Shared by the post chain's shaders (render/passes/post_pass.hpp); the CPU twins are in
// render/passes/post_reference.hpp.

// Luminance of linear Rec. 709 / sRGB primaries (ITU-R BT.709), as luminance() on the CPU.
float postLuminance(vec3 rgb) {
  return dot(rgb, vec3(0.2126, 0.7152, 0.0722));
}

// δ of the log-average log(δ + L) (Reinhard et al. 2002, eq. 1): kLogLuminanceDelta.
const float kPostLogDelta = 1e-4;
