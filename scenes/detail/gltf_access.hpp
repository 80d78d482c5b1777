#pragma once
// Checked reads from a parsed glTF file, shared by the glTF loaders in scenes/ (the bind-pose
// mesh loader and the character loader). Private to scenes/. Every failure names the file and
// the element: the accessor, buffer view or node, and what was expected.

#include <cstddef>
#include <cstdint>
#include <expected>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <tiny_gltf.h>

#include "common/error.hpp"

namespace mane::scenes::detail {

/// Everything a failure message needs: the file and the parsed model.
struct GltfContext {
  const tinygltf::Model& model;
  std::string file;

  [[nodiscard]] std::unexpected<Error> error(const std::string& what) const { return fail(file + ": " + what); }
};

/// Reads and parses a .gltf (JSON, buffers beside it or embedded) or .glb file, picking the
/// format by content. Images are not decoded: geometry never needs them, and a missing texture
/// must not fail a mesh. Fails when the file is missing, unreadable, truncated or not glTF.
[[nodiscard]] Result<tinygltf::Model> parseGltfFile(const std::filesystem::path& file);

/// Raw accessor contents, tightly packed: `count` elements of `elementSize` bytes, with the
/// sparse substitution applied (glTF 2.0 §3.6.2.3). An accessor without a buffer view starts
/// as zeros.
struct DenseAccessor {
  std::vector<unsigned char> bytes;
  std::size_t count = 0;
  int componentType = 0;
  int components = 0;
  bool normalized = false;
};

/// Accessor `index`, checked against its buffer view and buffer. `role` names the reader in
/// messages ("mesh 0 ('Cube') primitive 1 POSITION").
[[nodiscard]] Result<DenseAccessor> readAccessor(const GltfContext& ctx, int index, const std::string& role);

/// One component as a float; normalised integers map to [0, 1] or [-1, 1] (glTF 2.0 §3.11).
[[nodiscard]] float decodeComponent(const unsigned char* p, int type, bool normalized);

/// An accessor as floats, `components` per element (VEC2 → 2, VEC3 → 3, MAT4 → 16).
[[nodiscard]] Result<std::vector<float>> readFloats(const GltfContext& ctx, int index, int components,
                                                    const std::string& role);

/// A SCALAR accessor of unsigned byte, short or int: triangle indices.
[[nodiscard]] Result<std::vector<std::uint32_t>> readIndices(const GltfContext& ctx, int index,
                                                             const std::string& role);

/// An accessor of unsigned byte, short or int with `components` per element, as integers
/// (JOINTS_n: VEC4 of unsigned byte or short).
[[nodiscard]] Result<std::vector<std::uint32_t>> readUnsigned(const GltfContext& ctx, int index, int components,
                                                              const std::string& role);

/// The node's local matrix: its `matrix`, or T·R·S from its translation, rotation and scale.
[[nodiscard]] glm::mat4 nodeLocalMatrix(const tinygltf::Node& node);

/// The root nodes of the default scene (scene 0 when none is named; every node without a
/// parent when the file has no scenes). Fails when the default scene does not exist.
[[nodiscard]] Result<std::vector<int>> defaultSceneRoots(const GltfContext& ctx);

}  // namespace mane::scenes::detail
