#version 450
// Deep opacity maps, pass 1 (Yuksel & Keyser 2008 §3.1): only the depth test runs; the nearest
// hair depth per texel stays in the depth image.
void main() {}
