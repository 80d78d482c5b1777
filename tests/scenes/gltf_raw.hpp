#pragma once
// A glTF file read without tinygltf or the code under test: the JSON with nlohmann, accessors
// straight from the buffer bytes (byte offsets and strides as the spec lays them out). Tests use
// it to compute expected values independently. Handles .glb (JSON and BIN chunks) and .gltf
// with buffers in files beside it; no sparse accessors, no data URIs (the shared assets have
// none).

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <nlohmann/json.hpp>

#include "test_support.hpp"

namespace mane::scenes::testing {

struct RawGltf {
  nlohmann::json json;
  std::vector<std::string> buffers;

  static RawGltf read(const std::filesystem::path& file) {
    RawGltf raw;
    const std::string bytes = readFile(file);
    if (bytes.compare(0, 4, "glTF") == 0) {
      std::uint32_t jsonLength = 0;
      std::memcpy(&jsonLength, bytes.data() + 12, 4);
      raw.json = nlohmann::json::parse(bytes.substr(20, jsonLength));
      const std::size_t binHeader = 20 + jsonLength;
      std::uint32_t binLength = 0;
      std::memcpy(&binLength, bytes.data() + binHeader, 4);
      raw.buffers.push_back(bytes.substr(binHeader + 8, binLength));
    } else {
      raw.json = nlohmann::json::parse(bytes);
      for (const auto& buffer : raw.json.at("buffers")) {
        raw.buffers.push_back(readFile(file.parent_path() / buffer.at("uri").get<std::string>()));
      }
    }
    return raw;
  }

  /// Components per element of an accessor type.
  static int components(const std::string& type) {
    if (type == "SCALAR") return 1;
    if (type == "VEC2") return 2;
    if (type == "VEC3") return 3;
    if (type == "VEC4") return 4;
    if (type == "MAT4") return 16;
    throw std::runtime_error("unexpected accessor type " + type);
  }

  /// Accessor `index` as doubles, element after element: FLOAT, or unsigned byte/short read as
  /// plain integers (joint indices).
  [[nodiscard]] std::vector<double> accessor(int index) const {
    const auto& accessor = json.at("accessors").at(index);
    const auto& view = json.at("bufferViews").at(accessor.at("bufferView").get<int>());
    const std::string& buffer = buffers.at(view.at("buffer").get<std::size_t>());
    const int componentType = accessor.at("componentType").get<int>();
    const std::size_t componentSize = componentType == 5126 ? 4 : componentType == 5123 ? 2 : 1;
    const int perElement = components(accessor.at("type").get<std::string>());
    const std::size_t stride = view.value("byteStride", componentSize * perElement);
    const std::size_t start = view.value("byteOffset", std::size_t(0)) + accessor.value("byteOffset", std::size_t(0));
    const std::size_t count = accessor.at("count").get<std::size_t>();
    std::vector<double> out;
    for (std::size_t e = 0; e < count; ++e) {
      for (int c = 0; c < perElement; ++c) {
        const char* p = buffer.data() + start + e * stride + static_cast<std::size_t>(c) * componentSize;
        if (componentType == 5126) {
          float v;
          std::memcpy(&v, p, 4);
          out.push_back(v);
        } else if (componentType == 5123) {
          std::uint16_t v;
          std::memcpy(&v, p, 2);
          out.push_back(v);
        } else if (componentType == 5121) {
          out.push_back(static_cast<unsigned char>(*p));
        } else {
          throw std::runtime_error("unexpected component type " + std::to_string(componentType));
        }
      }
    }
    return out;
  }

  /// Node `index`'s local matrix from its JSON (matrix, or T·R·S), in double.
  [[nodiscard]] glm::dmat4 localMatrix(int index) const {
    const auto& node = json.at("nodes").at(index);
    if (node.contains("matrix")) {
      glm::dmat4 m;
      for (int i = 0; i < 16; ++i) m[i / 4][i % 4] = node.at("matrix").at(i).get<double>();
      return m;
    }
    const auto t = node.value("translation", std::vector<double>{0.0, 0.0, 0.0});
    const auto r = node.value("rotation", std::vector<double>{0.0, 0.0, 0.0, 1.0});
    const auto s = node.value("scale", std::vector<double>{1.0, 1.0, 1.0});
    glm::dmat4 m = glm::mat4_cast(glm::dquat(r[3], r[0], r[1], r[2]));
    for (int c = 0; c < 3; ++c) m[c] *= s[static_cast<std::size_t>(c)];
    m[3] = glm::dvec4(t[0], t[1], t[2], 1.0);
    return m;
  }

  /// Every node's world matrix, walking up the parents (in double).
  [[nodiscard]] std::vector<glm::dmat4> worldMatrices() const {
    const auto& nodes = json.at("nodes");
    std::vector<int> parent(nodes.size(), -1);
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      for (const auto& child : nodes[i].value("children", nlohmann::json::array())) {
        parent.at(child.get<std::size_t>()) = static_cast<int>(i);
      }
    }
    std::vector<glm::dmat4> world(nodes.size());
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      glm::dmat4 m = localMatrix(static_cast<int>(i));
      for (int p = parent[i]; p >= 0; p = parent[static_cast<std::size_t>(p)]) m = localMatrix(p) * m;
      world[i] = m;
    }
    return world;
  }
};

}  // namespace mane::scenes::testing
