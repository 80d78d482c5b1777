#include "scenes/detail/gltf_access.hpp"

#include <algorithm>
#include <cstring>
#include <exception>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

namespace mane::scenes::detail {
namespace {

// The most bytes one accessor may decode to: far beyond any asset we use, well below memory.
constexpr std::size_t kMaxAccessorBytes = std::size_t(1) << 30;

// Images are not needed for geometry; skipping them keeps loading fast and means a missing
// or corrupt texture cannot fail a mesh load.
bool skipImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;
}

/// Copies `length` bytes at `offset` inside buffer view `viewIndex` to `out`, checking
/// every index and range on the way.
Result<void> copyFromView(const GltfContext& ctx, int viewIndex, std::size_t offset, std::size_t stride,
                          std::size_t elementSize, std::size_t count, unsigned char* out, const std::string& what) {
  const auto& views = ctx.model.bufferViews;
  if (viewIndex < 0 || static_cast<std::size_t>(viewIndex) >= views.size()) {
    return ctx.error(what + " refers to buffer view " + std::to_string(viewIndex) + ", but the file has " +
                     std::to_string(views.size()) + " buffer views");
  }
  const tinygltf::BufferView& view = views[static_cast<std::size_t>(viewIndex)];
  if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= ctx.model.buffers.size()) {
    return ctx.error("buffer view " + std::to_string(viewIndex) + " refers to missing buffer " +
                     std::to_string(view.buffer));
  }
  const std::vector<unsigned char>& data = ctx.model.buffers[static_cast<std::size_t>(view.buffer)].data;
  if (count == 0) return {};
  // offset + (count − 1)·stride + elementSize ≤ byteLength, written so that no product or sum
  // can wrap around for hostile counts, strides or offsets.
  const bool viewFits = view.byteOffset <= data.size() && view.byteLength <= data.size() - view.byteOffset;
  const bool elementsFit = offset <= view.byteLength && elementSize <= view.byteLength - offset &&
                           count - 1 <= (view.byteLength - offset - elementSize) / stride;
  if (!viewFits || !elementsFit) {
    return ctx.error(what + " reads " + std::to_string(count) + " elements of " + std::to_string(elementSize) +
                     " bytes every " + std::to_string(stride) + " bytes from offset " + std::to_string(offset) +
                     " of buffer view " + std::to_string(viewIndex) + ", which holds " +
                     std::to_string(view.byteLength) + " bytes (buffer " + std::to_string(view.buffer) + " has " +
                     std::to_string(data.size()) + "): the file is truncated or the accessor is wrong");
  }
  const unsigned char* base = data.data() + view.byteOffset + offset;
  for (std::size_t i = 0; i < count; ++i) {
    std::memcpy(out + i * elementSize, base + i * stride, elementSize);
  }
  return {};
}

/// tinygltf's own messages for a bad .glb header are terse ("Invalid glTF binary."); check
/// the 12-byte header first so a truncated download says so.
Result<void> checkGlbHeader(const std::string& file, const std::vector<unsigned char>& bytes) {
  if (bytes.size() < 20) {
    return fail(file + ": truncated glTF binary: " + std::to_string(bytes.size()) +
                " bytes, shorter than the 20-byte header");
  }
  std::uint32_t declared = 0;
  std::memcpy(&declared, bytes.data() + 8, 4);
  if (declared > bytes.size()) {
    return fail(file + ": truncated glTF binary: the header declares " + std::to_string(declared) +
                " bytes but the file has " + std::to_string(bytes.size()));
  }
  return {};
}

/// Unsigned integer of 1, 2 or 4 bytes at `p`.
std::uint32_t decodeUnsigned(const unsigned char* p, std::size_t size) {
  if (size == 1) return *p;
  if (size == 2) {
    std::uint16_t v;
    std::memcpy(&v, p, 2);
    return v;
  }
  std::uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}

}  // namespace

Result<tinygltf::Model> parseGltfFile(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) {
    return fail(name + ": file not found");
  }
  std::ifstream stream(file, std::ios::binary);
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(stream)), std::istreambuf_iterator<char>());
  if (!stream.good() && !stream.eof()) return fail(name + ": could not read the file");
  if (bytes.size() > 0xFFFFFFFFu) return fail(name + ": file is larger than 4 GiB");

  tinygltf::Model model;
  std::string err;
  std::string warn;
  bool loaded = false;
  const bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
  try {
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(&skipImage, nullptr);
    const std::string baseDir = file.parent_path().string();
    if (binary) {
      if (auto ok = checkGlbHeader(name, bytes); !ok) return std::unexpected(ok.error());
      loaded = loader.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), static_cast<unsigned int>(bytes.size()),
                                           baseDir);
    } else {
      loaded = loader.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(bytes.data()),
                                          static_cast<unsigned int>(bytes.size()), baseDir);
    }
  } catch (const std::exception& e) {
    return fail(name + ": not a valid glTF file: " + e.what());
  }
  if (!loaded) {
    while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
    return fail(name + ": not a valid glTF file: " + (err.empty() ? "unknown error" : err));
  }
  return model;
}

Result<DenseAccessor> readAccessor(const GltfContext& ctx, int index, const std::string& role) {
  const auto& accessors = ctx.model.accessors;
  if (index < 0 || static_cast<std::size_t>(index) >= accessors.size()) {
    return ctx.error(role + " refers to accessor " + std::to_string(index) + ", but the file has " +
                     std::to_string(accessors.size()) + " accessors");
  }
  const tinygltf::Accessor& accessor = accessors[static_cast<std::size_t>(index)];
  const std::string what = role + " (accessor " + std::to_string(index) + ")";
  const int componentSize = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(accessor.componentType));
  const int components = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(accessor.type));
  if (componentSize <= 0 || components <= 0) {
    return ctx.error(what + " has an invalid component type " + std::to_string(accessor.componentType) + " or type " +
                     std::to_string(accessor.type));
  }
  DenseAccessor dense;
  dense.count = accessor.count;
  dense.componentType = accessor.componentType;
  dense.components = components;
  dense.normalized = accessor.normalized;
  const std::size_t elementSize = static_cast<std::size_t>(componentSize * components);
  // Checked before allocating: a count no buffer could back must not become a huge (or, once
  // multiplied, wrapped-around) allocation.
  if (dense.count > kMaxAccessorBytes / elementSize) {
    return ctx.error(what + " declares " + std::to_string(dense.count) + " elements of " + std::to_string(elementSize) +
                     " bytes, more than the " + std::to_string(kMaxAccessorBytes >> 20) + " MiB an accessor may hold");
  }
  dense.bytes.assign(dense.count * elementSize, 0);

  if (accessor.bufferView >= 0) {
    if (static_cast<std::size_t>(accessor.bufferView) >= ctx.model.bufferViews.size()) {
      return ctx.error(what + " refers to missing buffer view " + std::to_string(accessor.bufferView));
    }
    // ByteStride() is -1 when byteStride is not a multiple of the component size.
    const int stride = accessor.ByteStride(ctx.model.bufferViews[static_cast<std::size_t>(accessor.bufferView)]);
    if (stride <= 0) {
      return ctx.error(what + " has an invalid byte stride in buffer view " + std::to_string(accessor.bufferView));
    }
    if (auto copied = copyFromView(ctx, accessor.bufferView, accessor.byteOffset, static_cast<std::size_t>(stride),
                                   elementSize, dense.count, dense.bytes.data(), what);
        !copied) {
      return std::unexpected(copied.error());
    }
  }

  if (accessor.sparse.isSparse) {
    const auto& sparse = accessor.sparse;
    const std::size_t sparseCount = static_cast<std::size_t>(std::max(sparse.count, 0));
    const int indexType = sparse.indices.componentType;
    const int indexSize = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(indexType));
    if (indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
      return ctx.error(what + " has sparse indices of component type " + std::to_string(indexType) +
                       "; expected 5121, 5123 or 5125");
    }
    if (sparseCount > dense.count) {
      return ctx.error(what + " has " + std::to_string(sparseCount) + " sparse values but only " +
                       std::to_string(dense.count) + " elements");
    }
    std::vector<unsigned char> indexBytes(sparseCount * static_cast<std::size_t>(indexSize));
    std::vector<unsigned char> valueBytes(sparseCount * elementSize);
    if (auto ok = copyFromView(ctx, sparse.indices.bufferView, static_cast<std::size_t>(sparse.indices.byteOffset),
                               static_cast<std::size_t>(indexSize), static_cast<std::size_t>(indexSize), sparseCount,
                               indexBytes.data(), what + " sparse indices");
        !ok) {
      return std::unexpected(ok.error());
    }
    if (auto ok = copyFromView(ctx, sparse.values.bufferView, static_cast<std::size_t>(sparse.values.byteOffset),
                               elementSize, elementSize, sparseCount, valueBytes.data(), what + " sparse values");
        !ok) {
      return std::unexpected(ok.error());
    }
    for (std::size_t i = 0; i < sparseCount; ++i) {
      const std::uint32_t target = decodeUnsigned(indexBytes.data() + i * static_cast<std::size_t>(indexSize),
                                                  static_cast<std::size_t>(indexSize));
      if (target >= dense.count) {
        return ctx.error(what + " sparse index " + std::to_string(target) + " is past the accessor's count " +
                         std::to_string(dense.count));
      }
      std::memcpy(dense.bytes.data() + target * elementSize, valueBytes.data() + i * elementSize, elementSize);
    }
  }
  return dense;
}

/// One component as a float; normalised integers map to [0, 1] or [-1, 1] (glTF 2.0
/// §3.11, "Animations" table of normalisation formulas).
float decodeComponent(const unsigned char* p, int type, bool normalized) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      std::int8_t v;
      std::memcpy(&v, p, 1);
      return normalized ? std::max(static_cast<float>(v) / 127.0f, -1.0f) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? static_cast<float>(*p) / 255.0f : *p;
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      std::int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::max(static_cast<float>(v) / 32767.0f, -1.0f) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      std::uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? static_cast<float>(v) / 65535.0f : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      std::uint32_t v;
      std::memcpy(&v, p, 4);
      return static_cast<float>(v);
    }
    case TINYGLTF_COMPONENT_TYPE_INT: {
      std::int32_t v;
      std::memcpy(&v, p, 4);
      return static_cast<float>(v);
    }
    case TINYGLTF_COMPONENT_TYPE_DOUBLE: {
      double v;
      std::memcpy(&v, p, 8);
      return static_cast<float>(v);
    }
    default: {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
  }
}

/// A vertex attribute as floats, `components` per element (VEC2 → 2, VEC3 → 3).
Result<std::vector<float>> readFloats(const GltfContext& ctx, int index, int components, const std::string& role) {
  auto dense = readAccessor(ctx, index, role);
  if (!dense) return std::unexpected(dense.error());
  if (dense->components != components) {
    return ctx.error(role + " (accessor " + std::to_string(index) + ") has " + std::to_string(dense->components) +
                     " components per element; expected " + std::to_string(components));
  }
  const std::size_t size =
      static_cast<std::size_t>(tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(dense->componentType)));
  std::vector<float> out(dense->count * static_cast<std::size_t>(components));
  for (std::size_t i = 0; i < out.size(); ++i) {
    out[i] = decodeComponent(dense->bytes.data() + i * size, dense->componentType, dense->normalized);
  }
  return out;
}

Result<std::vector<std::uint32_t>> readIndices(const GltfContext& ctx, int index, const std::string& role) {
  auto dense = readAccessor(ctx, index, role);
  if (!dense) return std::unexpected(dense.error());
  const int type = dense->componentType;
  if (dense->components != 1 ||
      (type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
       type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)) {
    return ctx.error(role + " (accessor " + std::to_string(index) +
                     ") must be SCALAR unsigned byte, short or int; it has component type " + std::to_string(type) +
                     " and " + std::to_string(dense->components) + " components");
  }
  const std::size_t size =
      static_cast<std::size_t>(tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(type)));
  std::vector<std::uint32_t> out(dense->count);
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = decodeUnsigned(dense->bytes.data() + i * size, size);
  return out;
}

Result<std::vector<std::uint32_t>> readUnsigned(const GltfContext& ctx, int index, int components,
                                                const std::string& role) {
  auto dense = readAccessor(ctx, index, role);
  if (!dense) return std::unexpected(dense.error());
  const int type = dense->componentType;
  if (dense->components != components ||
      (type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
       type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)) {
    return ctx.error(role + " (accessor " + std::to_string(index) + ") must hold " + std::to_string(components) +
                     " unsigned bytes, shorts or ints per element; it has component type " + std::to_string(type) +
                     " and " + std::to_string(dense->components) + " components");
  }
  const std::size_t size =
      static_cast<std::size_t>(tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(type)));
  std::vector<std::uint32_t> out(dense->count * static_cast<std::size_t>(components));
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = decodeUnsigned(dense->bytes.data() + i * size, size);
  return out;
}

glm::mat4 nodeLocalMatrix(const tinygltf::Node& node) {
  if (node.matrix.size() == 16) {
    glm::dmat4 m = glm::make_mat4(node.matrix.data());  // both column-major
    return glm::mat4(m);
  }
  glm::mat4 m(1.0f);
  if (node.translation.size() == 3) {
    m[3] = glm::vec4(glm::vec3(glm::make_vec3(node.translation.data())), 1.0f);
  }
  if (node.rotation.size() == 4) {
    // glTF stores (x, y, z, w); glm::quat's constructor takes w first.
    const glm::quat q(static_cast<float>(node.rotation[3]), static_cast<float>(node.rotation[0]),
                      static_cast<float>(node.rotation[1]), static_cast<float>(node.rotation[2]));
    m = m * glm::mat4_cast(q);
  }
  if (node.scale.size() == 3) {
    const glm::vec3 s(glm::make_vec3(node.scale.data()));
    m[0] *= s.x;
    m[1] *= s.y;
    m[2] *= s.z;
  }
  return m;
}

Result<std::vector<int>> defaultSceneRoots(const GltfContext& ctx) {
  const tinygltf::Model& model = ctx.model;
  std::vector<int> roots;
  if (!model.scenes.empty()) {
    const int sceneIndex = model.defaultScene >= 0 ? model.defaultScene : 0;
    if (static_cast<std::size_t>(sceneIndex) >= model.scenes.size()) {
      return ctx.error("the default scene " + std::to_string(sceneIndex) + " does not exist");
    }
    roots = model.scenes[static_cast<std::size_t>(sceneIndex)].nodes;
  } else {
    // No scene: glTF leaves the choice to the application; take every root node.
    std::vector<bool> isChild(model.nodes.size(), false);
    for (const auto& node : model.nodes) {
      for (int child : node.children) {
        if (child >= 0 && static_cast<std::size_t>(child) < isChild.size()) {
          isChild[static_cast<std::size_t>(child)] = true;
        }
      }
    }
    for (std::size_t i = 0; i < model.nodes.size(); ++i) {
      if (!isChild[i]) roots.push_back(static_cast<int>(i));
    }
  }
  return roots;
}

}  // namespace mane::scenes::detail
