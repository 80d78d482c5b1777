#version 450
// HDR scene colour → display: a linear exposure scale; the sRGB attachment encodes on write.
layout(set = 0, binding = 0) uniform sampler2D hdrColor;
layout(push_constant) uniform Output { float exposure; } settings;
layout(location = 0) in vec2 inUv;
layout(location = 0) out vec4 outColor;

void main() {
  outColor = vec4(clamp(texture(hdrColor, inUv).rgb * settings.exposure, 0.0, 1.0), 1.0);
}
