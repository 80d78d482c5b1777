#version 450
// Positions already in clip space; one colour for the draw. Used by tests and overlays.
layout(location = 0) in vec2 inPosition;
void main() { gl_Position = vec4(inPosition, 0.0, 1.0); }
