#version 450
#extension GL_GOOGLE_include_directive : require
// One shell per instance (render/passes/fur_pass.hpp): the mesh pushed out along its normal to
// the height of its layer. Instance 0 is layer N (the skin), drawn first so that its depth hides
// what lies behind the body; instance N − 1 is layer 1, the top. The fur is lit here, per
// vertex: a shell's fragments, N of them over each pixel of the body, only read the photo.
#include "fur_common.glsl"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;

layout(location = 0) out vec3 outDiffuse;   // FurLight
layout(location = 1) out vec3 outSpecular;
layout(location = 2) out vec2 outUv;
layout(location = 3) flat out uint outLayer;

// Per vertex, world space, units of h_b (FurPass::setLeans).
layout(set = 0, binding = 4) readonly buffer VertexLeans {
  vec4 vertexLeans[];
};

void main() {
  uint layers = layerCount();
  uint layer = layers - uint(gl_InstanceIndex);
  // Layer n lies h_b·n/N below the fur's top (Ukaji et al. eq. 3), so at s = 1 − n/N of h_b.
  float s = 1.0 - float(layer) / float(layers);
  vec3 normal = normalize(mat3(fur.normalMatrix) * inNormal);
  vec3 lean = furLean(normal, vertexLeans[gl_VertexIndex].xyz);
  vec3 world = (fur.model * vec4(inPosition, 1.0)).xyz + furOffset(normal, lean, s);
  FurLight lit = furLight(normal, furDirection(normal, lean, s), world);
  outDiffuse = lit.diffuse;
  outSpecular = lit.specular;
  outUv = photoCoordinates(inUv, inPosition, inNormal);
  outLayer = layer;
  gl_Position = fur.viewProjection * vec4(world, 1.0);
}
