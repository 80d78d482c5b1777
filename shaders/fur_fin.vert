#version 450
#extension GL_GOOGLE_include_directive : require
// Fins (Lengyel et al. 2001) on the silhouette edges the CPU found this frame
// (render/passes/fur_pass.hpp): six vertices per edge, no vertex buffer. Fin f reads its edge's
// two vertex indices and puts up a quad from the skin to the top shell along the vertex normals,
// the same offsets the shells use, so fin and shells meet without cracks.
#include "fur_common.glsl"

// The mesh, 8 floats per vertex: position xyz, normal xyz, uv.
layout(set = 0, binding = 2) readonly buffer MeshVertices {
  float meshVertices[];
};
layout(set = 0, binding = 3) readonly buffer FinEdges {
  uvec2 finEdges[];
};
layout(set = 0, binding = 4) readonly buffer VertexLeans {
  vec4 vertexLeans[];
};

layout(location = 0) out vec3 outWorld;
layout(location = 1) out vec3 outNormal;
layout(location = 2) out vec2 outUv;
layout(location = 3) out float outHeight;            // 0 at the skin … 1 at the top shell
layout(location = 4) flat out vec2 outAcross;       // uv step across the edge
layout(location = 5) out vec3 outDirection;

vec3 meshVec3(uint vertex, uint offset) {
  uint base = vertex * 8u + offset;
  return vec3(meshVertices[base], meshVertices[base + 1u], meshVertices[base + 2u]);
}

vec2 meshUv(uint vertex) {
  uint base = vertex * 8u + 6u;
  return vec2(meshVertices[base], meshVertices[base + 1u]);
}

void main() {
  // Corners (along the edge, up the fin) of two triangles.
  const vec2 corners[6] = vec2[6](vec2(0, 0), vec2(1, 0), vec2(1, 1), vec2(0, 0), vec2(1, 1), vec2(0, 1));
  uvec2 edge = finEdges[gl_VertexIndex / 6];
  vec2 corner = corners[gl_VertexIndex % 6];
  uint vertex = corner.x < 0.5 ? edge.x : edge.y;
  vec3 normal = normalize(mat3(fur.normalMatrix) * meshVec3(vertex, 3u));
  uint layers = layerCount();
  float s = corner.y * (1.0 - 1.0 / float(layers));  // up to layer 1, the top shell
  vec3 lean = furLean(normal, vertexLeans[vertex].xyz);
  vec3 world = (fur.model * vec4(meshVec3(vertex, 0u), 1.0)).xyz + furOffset(normal, lean, s);
  vec2 uvAlong = photoCoordinates(meshUv(edge.y), meshVec3(edge.y, 0u), meshVec3(edge.y, 3u)) -
                photoCoordinates(meshUv(edge.x), meshVec3(edge.x, 0u), meshVec3(edge.x, 3u));
  outWorld = world;
  outNormal = normal;
  outUv = photoCoordinates(meshUv(vertex), meshVec3(vertex, 0u), meshVec3(vertex, 3u));
  outDirection = furDirection(normal, lean, s);
  outHeight = corner.y;
  outAcross = 0.5 * vec2(-uvAlong.y, uvAlong.x);
  gl_Position = fur.viewProjection * vec4(world, 1.0);
}
