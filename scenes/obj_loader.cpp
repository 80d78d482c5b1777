#include "scenes/obj_loader.hpp"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <tuple>

#include <tiny_obj_loader.h>

#include "scenes/gltf_loader.hpp"

namespace mane::scenes {
namespace {

/// Checks one index against its list; `kind` names the list for the message.
Result<void> checkIndex(const std::string& file, int index, std::size_t size, const char* kind, std::size_t face,
                        bool optional) {
  if (optional && index == -1) return {};
  if (index < 0 || static_cast<std::size_t>(index) >= size) {
    // tinyobj has already turned the file's 1-based (or negative, relative) index into a
    // 0-based one; report it the way the file counts.
    return fail(file + ": face " + std::to_string(face + 1) + " refers to " + kind + " " +
                std::to_string(static_cast<long long>(index) + 1) + ", but the file defines " + std::to_string(size) +
                " " + kind + (size == 1 ? "" : "s") + " (index out of range)");
  }
  return {};
}

/// `text` with its `vw` lines (tinyobjloader's skin-weight extension) turned into comments. No
/// skin weights are read from OBJ here, and tinyobjloader 2.0.0rc10 converts their joint ids from
/// float to int unchecked, undefined behaviour for an id beyond int's range. A line starts after
/// '\n' or '\r' and its keyword after spaces and tabs, as tinyobjloader splits and trims them.
std::string withoutSkinWeights(std::string text) {
  bool atLineStart = true;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n' || c == '\r') {
      atLineStart = true;
    } else if (atLineStart && c != ' ' && c != '\t') {
      atLineStart = false;
      if (c == 'v' && i + 2 < text.size() && text[i + 1] == 'w' && (text[i + 2] == ' ' || text[i + 2] == '\t'))
        text[i] = '#';
    }
  }
  return text;
}

/// The 1-based line of the first number in `text` whose exponent has ten digits or more (leading
/// zeros aside), or 0 if there is none. tinyobjloader 2.0.0rc10 sums an exponent's digits in an
/// int whose overflow, at 2147483648, is undefined behaviour; any exponent that long is far
/// beyond a float's range. Lines are counted as tinyobjloader splits them ('\n', '\r' or "\r\n").
std::size_t lineWithOverlongExponent(const std::string& text) {
  const auto digit = [&](std::size_t i) { return i < text.size() && text[i] >= '0' && text[i] <= '9'; };
  std::size_t line = 1;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n' || (c == '\r' && (i + 1 == text.size() || text[i + 1] != '\n'))) ++line;
    if ((c != 'e' && c != 'E') || i == 0 || !(digit(i - 1) || text[i - 1] == '.')) continue;
    std::size_t at = i + 1;
    if (at < text.size() && (text[at] == '+' || text[at] == '-')) ++at;
    while (at < text.size() && text[at] == '0') ++at;
    std::size_t digits = 0;
    while (digit(at + digits)) ++digits;
    if (digits >= 10) return line;
  }
  return 0;
}

}  // namespace

Result<Mesh> loadObj(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) return fail(name + ": file not found");

  tinyobj::ObjReaderConfig config;
  // Triangulate ourselves after the index check: tinyobj's own triangulation reads
  // positions through unchecked indices.
  config.triangulate = false;
  config.vertex_color = false;
  std::ifstream in(file, std::ios::binary);
  if (!in) return fail(name + ": cannot open the file");
  std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (const std::size_t line = lineWithOverlongExponent(text); line != 0)
    return fail(name + ": line " + std::to_string(line) +
                ": a number's exponent has ten digits or more (far beyond a float's range)");
  tinyobj::ObjReader reader;
  bool parsed = false;
  try {
    // From memory, with no material library: materials are not read (obj_loader.hpp).
    parsed = reader.ParseFromString(withoutSkinWeights(std::move(text)), "", config);
  } catch (const std::exception& e) {
    return fail(name + ": not a valid OBJ file: " + e.what());
  }
  if (!parsed) {
    std::string reason = reader.Error();
    while (!reason.empty() && std::isspace(static_cast<unsigned char>(reason.back()))) {
      reason.pop_back();
    }
    return fail(name + ": not a valid OBJ file: " + (reason.empty() ? "unknown error" : reason));
  }

  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  const std::size_t positionCount = attrib.vertices.size() / 3;
  const std::size_t normalCount = attrib.normals.size() / 3;
  const std::size_t uvCount = attrib.texcoords.size() / 2;

  Mesh mesh;
  mesh.name = file.stem().string();

  // Positions only (scans, cages): keep the file's numbering, vertex i = the i-th `v` line,
  // so counts match the file and subdivision sees the cage's own vertex ids.
  bool positionsOnly = true;
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    for (const tinyobj::index_t& index : shape.mesh.indices) {
      if (index.normal_index != -1 || index.texcoord_index != -1) positionsOnly = false;
    }
  }
  if (positionsOnly) {
    mesh.positions.reserve(positionCount);
    for (std::size_t v = 0; v < positionCount; ++v) {
      mesh.positions.emplace_back(attrib.vertices[3 * v], attrib.vertices[3 * v + 1], attrib.vertices[3 * v + 2]);
    }
  }

  bool anyNormal = false;
  bool anyUv = false;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec2> uvs;
  // One output vertex per distinct (position, uv, normal) triple, in first-use order.
  std::map<std::tuple<int, int, int>, std::uint32_t> vertexOf;
  std::vector<std::uint32_t> corners;
  std::size_t faceNumber = 0;

  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    std::size_t offset = 0;
    for (const auto arity : shape.mesh.num_face_vertices) {
      corners.clear();
      for (std::size_t c = 0; c < arity; ++c) {
        const tinyobj::index_t& index = shape.mesh.indices[offset + c];
        if (auto ok = checkIndex(name, index.vertex_index, positionCount, "vertex", faceNumber, false); !ok) {
          return std::unexpected(ok.error());
        }
        if (auto ok = checkIndex(name, index.normal_index, normalCount, "normal", faceNumber, true); !ok) {
          return std::unexpected(ok.error());
        }
        if (auto ok = checkIndex(name, index.texcoord_index, uvCount, "texture coordinate", faceNumber, true); !ok) {
          return std::unexpected(ok.error());
        }
        if (positionsOnly) {
          corners.push_back(static_cast<std::uint32_t>(index.vertex_index));
          continue;
        }
        const auto key = std::make_tuple(index.vertex_index, index.texcoord_index, index.normal_index);
        auto [it, inserted] = vertexOf.try_emplace(key, static_cast<std::uint32_t>(mesh.positions.size()));
        if (inserted) {
          const auto v = static_cast<std::size_t>(index.vertex_index);
          mesh.positions.emplace_back(attrib.vertices[3 * v], attrib.vertices[3 * v + 1], attrib.vertices[3 * v + 2]);
          if (index.normal_index >= 0) {
            const auto n = static_cast<std::size_t>(index.normal_index);
            normals.emplace_back(attrib.normals[3 * n], attrib.normals[3 * n + 1], attrib.normals[3 * n + 2]);
            anyNormal = true;
          } else {
            normals.emplace_back(0.0f);
          }
          if (index.texcoord_index >= 0) {
            const auto t = static_cast<std::size_t>(index.texcoord_index);
            // OBJ puts v = 0 at the bottom of the image; glTF and Vulkan at the top.
            uvs.emplace_back(attrib.texcoords[2 * t], 1.0f - attrib.texcoords[2 * t + 1]);
            anyUv = true;
          } else {
            uvs.emplace_back(0.0f);
          }
        }
        corners.push_back(it->second);
      }
      for (std::size_t c = 1; c + 1 < corners.size(); ++c) {
        mesh.indices.push_back(corners[0]);
        mesh.indices.push_back(corners[c]);
        mesh.indices.push_back(corners[c + 1]);
      }
      offset += arity;
      ++faceNumber;
    }
  }
  if (mesh.indices.empty()) {
    return fail(name + ": the OBJ file has no faces with three or more corners");
  }
  if (positionsOnly) {
    computeSmoothNormals(mesh);
    return mesh;
  }
  if (anyUv) mesh.uvs = std::move(uvs);
  const bool allNormals =
      std::all_of(vertexOf.begin(), vertexOf.end(), [](const auto& entry) { return std::get<2>(entry.first) >= 0; });
  if (anyNormal && allNormals) {
    mesh.normals = std::move(normals);
  } else {
    computeSmoothNormals(mesh);
  }
  return mesh;
}

Result<Mesh> loadMesh(const std::filesystem::path& file) {
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".gltf" || extension == ".glb") return loadGltf(file);
  if (extension == ".obj") return loadObj(file);
  return fail(file.string() + ": unsupported mesh format '" + extension + "'; expected .gltf, .glb or .obj");
}

}  // namespace mane::scenes
