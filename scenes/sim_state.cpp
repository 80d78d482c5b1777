#include "scenes/sim_state.hpp"

#include <bit>
#include <cstring>
#include <fstream>

#include "scenes/world.hpp"

namespace mane::scenes {
namespace {

// The file is little-endian; values are copied as the host holds them.
static_assert(std::endian::native == std::endian::little, "the .msim format is little-endian; add byte swapping");

constexpr char kSignature[8] = {'M', 'A', 'N', 'E', 'S', 'I', 'M', '\0'};
constexpr std::uint32_t kVersion = 1;
constexpr std::uint64_t kHeaderBytes = 48;

class ByteWriter {
public:
  template <class T>
  void value(const T& v) {
    const auto* p = reinterpret_cast<const unsigned char*>(&v);
    bytes_.insert(bytes_.end(), p, p + sizeof v);
  }
  void text(const std::string& s) {
    value(static_cast<std::uint32_t>(s.size()));
    bytes_.insert(bytes_.end(), s.begin(), s.end());
  }
  void points(const std::vector<glm::vec3>& points) {
    for (const glm::vec3& p : points) value(p.x), value(p.y), value(p.z);
  }
  std::vector<unsigned char> take() { return std::move(bytes_); }

private:
  std::vector<unsigned char> bytes_;
};

/// Reads values at a cursor, each checked against the end first; errors name the byte offset.
class ByteReader {
public:
  ByteReader(std::span<const unsigned char> bytes, const std::string& name) : bytes_(bytes), name_(name) {}

  template <class T>
  Result<T> value(const char* what) {
    if (auto room = need(sizeof(T), what); !room) return std::unexpected(room.error());
    T v;
    std::memcpy(&v, bytes_.data() + at_, sizeof v);
    at_ += sizeof v;
    return v;
  }
  Result<std::string> text(const char* what) {
    auto size = value<std::uint32_t>(what);
    if (!size) return std::unexpected(size.error());
    if (auto room = need(*size, what); !room) return std::unexpected(room.error());
    std::string s(reinterpret_cast<const char*>(bytes_.data() + at_), *size);
    at_ += *size;
    return s;
  }
  Result<std::vector<glm::vec3>> points(std::uint64_t count, const char* what) {
    if (auto room = need(12 * count, what); !room) return std::unexpected(room.error());
    std::vector<glm::vec3> result(count);
    // An empty vector's data() may be null, and memcpy may not be given null even for 0 bytes.
    if (count > 0) std::memcpy(result.data(), bytes_.data() + at_, 12 * count);
    at_ += 12 * count;
    return result;
  }
  /// Moves past `count` bytes the caller has checked.
  void skip(std::uint64_t count) { at_ += count; }
  std::uint64_t offset() const { return at_; }
  bool atEnd() const { return at_ == bytes_.size(); }
  Error error(const std::string& what) const { return {name_ + ": " + what}; }

private:
  Result<void> need(std::uint64_t count, const char* what) const {
    if (count > bytes_.size() - at_)
      return fail(name_ + ": " + what + " needs " + std::to_string(count) + " bytes at byte " + std::to_string(at_) +
                  ", but the file ends at byte " + std::to_string(bytes_.size()) + " (truncated)");
    return {};
  }

  std::span<const unsigned char> bytes_;
  std::string name_;
  std::uint64_t at_ = 0;
};

// Binds `variable` to the value of `expression` (a Result), or returns its error.
#define MANE_READ(variable, expression)                                \
  auto variable##Read = (expression);                                  \
  if (!variable##Read) return std::unexpected(variable##Read.error()); \
  auto variable = std::move(*variable##Read)

}  // namespace

SimulatedState captureSimulatedState(const World& world, std::uint64_t step) {
  SimulatedState state{.step = step, .time = world.time(), .stateHash = world.stateHash()};
  for (std::size_t g = 0; g < world.simulatedGroomCount(); ++g) {
    const physics::HairSystem& hair = world.simulatedGroom(g);
    GroomState groom{.name = world.simulatedGroomName(g),
                     .positions = hair.particles().positions,
                     .previousPositions = hair.particles().previousPositions};
    for (const physics::GuideStrand& strand : hair.strands()) groom.pointsPerStrand.push_back(strand.particleCount);
    state.grooms.push_back(std::move(groom));
  }
  for (std::size_t c = 0; c < world.cloths().size(); ++c) {
    const physics::Particles& particles = world.cloths()[c].cloth().particles();
    state.cloths.push_back({.name = world.scene().cloths[c].name,
                            .positions = particles.positions,
                            .previousPositions = particles.previousPositions});
  }
  for (const World::FurLeans& fur : world.furLeans())
    state.furs.push_back({.fur = static_cast<std::uint32_t>(fur.fur), .leans = {fur.leans.begin(), fur.leans.end()}});
  return state;
}

std::vector<unsigned char> encodeSimulatedState(const SimulatedState& state) {
  ByteWriter out;
  for (char c : kSignature) out.value(c);
  out.value(kVersion);
  out.value(static_cast<std::uint32_t>(state.grooms.size()));
  out.value(static_cast<std::uint32_t>(state.cloths.size()));
  out.value(static_cast<std::uint32_t>(state.furs.size()));
  out.value(state.step);
  out.value(state.time);
  out.value(state.stateHash);
  for (const GroomState& groom : state.grooms) {
    out.text(groom.name);
    out.value(static_cast<std::uint32_t>(groom.pointsPerStrand.size()));
    out.value(static_cast<std::uint32_t>(groom.positions.size()));
    for (std::uint32_t points : groom.pointsPerStrand) out.value(points);
    out.points(groom.positions);
    out.points(groom.previousPositions);
  }
  for (const ClothState& cloth : state.cloths) {
    out.text(cloth.name);
    out.value(static_cast<std::uint32_t>(cloth.positions.size()));
    out.points(cloth.positions);
    out.points(cloth.previousPositions);
  }
  for (const FurLeanState& fur : state.furs) {
    out.value(fur.fur);
    out.value(static_cast<std::uint32_t>(fur.leans.size()));
    out.points(fur.leans);
  }
  return out.take();
}

Result<SimulatedState> decodeSimulatedState(std::span<const unsigned char> bytes, const std::string& name) {
  ByteReader in(bytes, name);
  if (bytes.size() < kHeaderBytes || std::memcmp(bytes.data(), kSignature, sizeof kSignature) != 0)
    return std::unexpected(
        in.error("not a mane simulation state: it does not start with the 8-byte signature "
                 "\"MANESIM\\0\" and a 48-byte header"));
  in.skip(sizeof kSignature);  // checked above
  MANE_READ(version, in.value<std::uint32_t>("the version"));
  if (version != kVersion)
    return std::unexpected(in.error("version " + std::to_string(version) + " at byte 8; this program reads version " +
                                    std::to_string(kVersion)));
  MANE_READ(groomCount, in.value<std::uint32_t>("the groom count"));
  MANE_READ(clothCount, in.value<std::uint32_t>("the cloth count"));
  MANE_READ(furCount, in.value<std::uint32_t>("the fur count"));
  SimulatedState state;
  MANE_READ(step, in.value<std::uint64_t>("the step"));
  MANE_READ(time, in.value<double>("the time"));
  MANE_READ(hash, in.value<std::uint64_t>("the state hash"));
  state.step = step, state.time = time, state.stateHash = hash;
  for (std::uint32_t g = 0; g < groomCount; ++g) {
    GroomState groom;
    const std::uint64_t start = in.offset();
    MANE_READ(groomName, in.text("a groom name"));
    MANE_READ(strands, in.value<std::uint32_t>("a groom's strand count"));
    MANE_READ(particles, in.value<std::uint32_t>("a groom's particle count"));
    if (std::uint64_t{strands} * 4 > bytes.size())
      return std::unexpected(in.error("groom " + std::to_string(g) + " at byte " + std::to_string(start) +
                                      " declares " + std::to_string(strands) +
                                      " strands, more than the file can hold"));
    std::uint64_t total = 0;
    for (std::uint32_t s = 0; s < strands; ++s) {
      const std::uint64_t at = in.offset();
      MANE_READ(points, in.value<std::uint32_t>("a strand's point count"));
      if (points < 2)
        return std::unexpected(in.error("groom '" + groomName + "' strand " + std::to_string(s) + " has " +
                                        std::to_string(points) + " points (byte " + std::to_string(at) +
                                        "); a guide has at least 2"));
      total += points;
      groom.pointsPerStrand.push_back(points);
    }
    if (total != particles)
      return std::unexpected(in.error("groom '" + groomName + "': its strands' point counts add up to " +
                                      std::to_string(total) + ", not the " + std::to_string(particles) +
                                      " particles its record declares (byte " + std::to_string(start) + ")"));
    MANE_READ(positions, in.points(particles, "a groom's positions"));
    MANE_READ(previous, in.points(particles, "a groom's previous positions"));
    groom.name = std::move(groomName), groom.positions = std::move(positions);
    groom.previousPositions = std::move(previous);
    state.grooms.push_back(std::move(groom));
  }
  for (std::uint32_t c = 0; c < clothCount; ++c) {
    MANE_READ(clothName, in.text("a cloth name"));
    MANE_READ(particles, in.value<std::uint32_t>("a cloth's particle count"));
    MANE_READ(positions, in.points(particles, "a cloth's positions"));
    MANE_READ(previous, in.points(particles, "a cloth's previous positions"));
    state.cloths.push_back(
        {.name = std::move(clothName), .positions = std::move(positions), .previousPositions = std::move(previous)});
  }
  for (std::uint32_t f = 0; f < furCount; ++f) {
    MANE_READ(fur, in.value<std::uint32_t>("a fur index"));
    MANE_READ(vertices, in.value<std::uint32_t>("a fur's vertex count"));
    MANE_READ(leans, in.points(vertices, "a fur's leans"));
    state.furs.push_back({.fur = fur, .leans = std::move(leans)});
  }
  if (!in.atEnd())
    return std::unexpected(in.error(std::to_string(bytes.size() - in.offset()) +
                                    " bytes left over after the last "
                                    "record, from byte " +
                                    std::to_string(in.offset()) + " (not a version-" + std::to_string(kVersion) +
                                    " file?)"));
  return state;
}

Result<void> writeFileBytes(const std::filesystem::path& file, std::span<const unsigned char> bytes) {
  std::error_code error;
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path(), error);
  if (error) return fail(file.string() + ": cannot create its folder: " + error.message());
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (!out.flush()) return fail(file.string() + ": cannot write the file");
  return {};
}

Result<std::vector<unsigned char>> readFileBytes(const std::filesystem::path& file) {
  std::error_code error;
  const auto size = std::filesystem::file_size(file, error);
  if (error) return fail(file.string() + ": cannot read the file: " + error.message());
  std::vector<unsigned char> bytes(size);
  std::ifstream in(file, std::ios::binary);
  if (!in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size)))
    return fail(file.string() + ": cannot read the file");
  return bytes;
}

Result<void> writeSimulatedState(const std::filesystem::path& file, const SimulatedState& state) {
  return writeFileBytes(file, encodeSimulatedState(state));
}

Result<SimulatedState> readSimulatedState(const std::filesystem::path& file) {
  auto bytes = readFileBytes(file);
  if (!bytes) return std::unexpected(bytes.error());
  return decodeSimulatedState(*bytes, file.string());
}

#undef MANE_READ

}  // namespace mane::scenes
