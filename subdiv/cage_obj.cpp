#include "subdiv/cage_obj.hpp"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace mane::subdiv {
namespace {

std::vector<std::string_view> splitWhitespace(std::string_view line) {
  std::vector<std::string_view> tokens;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
  return tokens;
}

// Built with append: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string.
std::string quoted(std::string_view text) {
  std::string result(1, '\'');
  result.append(text);
  result.push_back('\'');
  return result;
}

template <class Number>
bool parseNumber(std::string_view token, Number& value) {
  const char* end = token.data() + token.size();
  // from_chars rejects a leading '+', which some exporters write.
  const char* begin = (!token.empty() && token.front() == '+') ? token.data() + 1 : token.data();
  const auto [last, error] = std::from_chars(begin, end, value);
  return error == std::errc() && last == end;
}

/// Parses one file line after another, remembering where faces and tags came from so that
/// validation errors can point at a line.
class CageObjParser {
public:
  explicit CageObjParser(std::string_view sourceName) : source_(sourceName) {}

  Result<Cage> parse(std::string_view text) {
    std::size_t lineNumber = 0;
    std::size_t position = 0;
    while (position <= text.size()) {
      std::size_t end = text.find('\n', position);
      if (end == std::string_view::npos) end = text.size();
      ++lineNumber;
      line_ = lineNumber;
      if (auto parsed = parseLine(text.substr(position, end - position)); !parsed)
        return std::unexpected(parsed.error());
      position = end + 1;
    }
    return finish();
  }

private:
  std::unexpected<Error> problem(const std::string& what) const { return problemAt(line_, what); }
  std::unexpected<Error> problemAt(std::size_t line, const std::string& what) const {
    return fail(std::string(source_) + ":" + std::to_string(line) + ": " + what);
  }

  Result<void> parseLine(std::string_view line) {
    if (const std::size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    const std::vector<std::string_view> tokens = splitWhitespace(line);
    if (tokens.empty()) return {};
    const std::string_view keyword = tokens.front();
    if (keyword == "v") return parseVector(tokens, 3, 4, "a vertex position");
    if (keyword == "vt") return parseVector(tokens, 2, 3, "a texture coordinate");
    if (keyword == "vn") return {};
    if (keyword == "f") return parseFace(tokens);
    if (keyword == "t") return parseTag(tokens);
    if (keyword == "o" || keyword == "g" || keyword == "s" || keyword == "usemtl" || keyword == "mtllib") return {};
    return problem("unknown statement '" + std::string(keyword) + "'; a cage has v, vt, vn, f and t lines");
  }

  Result<void> parseVector(const std::vector<std::string_view>& tokens, std::size_t least, std::size_t most,
                           const std::string& what) {
    const std::size_t count = tokens.size() - 1;
    if (count < least || count > most)
      return problem(std::string(tokens[0]) + " needs " + std::to_string(least) + " numbers for " + what + ", found " +
                     std::to_string(count));
    float values[3] = {0.0f, 0.0f, 0.0f};
    for (std::size_t i = 0; i < least; ++i)
      if (!parseNumber(tokens[i + 1], values[i]) || !std::isfinite(values[i]))
        return problem(quoted(tokens[i + 1]) + " in " + what + " is not a finite number");
    if (least == 3)
      cage_.positions.emplace_back(values[0], values[1], values[2]);
    else
      cage_.uvs.emplace_back(values[0], values[1]);
    return {};
  }

  /// An OBJ index (1-based, or negative counting back from the last element so far) → 0-based.
  Result<std::uint32_t> resolveIndex(std::string_view token, std::size_t count, const std::string& what) const {
    long long index = 0;
    if (!parseNumber(token, index) || index == 0)
      return problem(quoted(token) + " is not a valid " + what + " index (1-based, or negative)");
    const long long resolved = index > 0 ? index - 1 : static_cast<long long>(count) + index;
    if (resolved < 0 || resolved >= static_cast<long long>(count))
      return problem(what + " index " + std::to_string(index) + " is out of range: " + std::to_string(count) +
                     " defined so far");
    return static_cast<std::uint32_t>(resolved);
  }

  Result<void> parseFace(const std::vector<std::string_view>& tokens) {
    if (tokens.size() < 4)
      return problem("a face needs at least 3 vertices, found " + std::to_string(tokens.size() - 1));
    bool faceHasUvs = false;
    for (std::size_t i = 1; i < tokens.size(); ++i) {
      const std::string_view corner = tokens[i];
      const std::size_t slash = corner.find('/');
      auto vertex = resolveIndex(corner.substr(0, slash), cage_.positions.size(), "vertex");
      if (!vertex) return std::unexpected(vertex.error());
      cage_.faceVertices.push_back(*vertex);
      std::string_view uvToken;
      if (slash != std::string_view::npos) {
        const std::size_t secondSlash = corner.find('/', slash + 1);
        uvToken = corner.substr(
            slash + 1, secondSlash == std::string_view::npos ? std::string_view::npos : secondSlash - slash - 1);
      }
      const bool cornerHasUv = !uvToken.empty();
      if (i == 1) faceHasUvs = cornerHasUv;
      if (cornerHasUv != faceHasUvs)
        return problem("some corners of this face have texture coordinates and some do not");
      if (cornerHasUv) {
        auto uv = resolveIndex(uvToken, cage_.uvs.size(), "texture coordinate");
        if (!uv) return std::unexpected(uv.error());
        cage_.faceUvIndices.push_back(*uv);
      }
    }
    // UVs are all or nothing: a cage with textured and untextured faces has no usable UV channel.
    if (cage_.faceSizes.empty()) firstFaceHasUvs_ = faceHasUvs;
    if (faceHasUvs != firstFaceHasUvs_)
      return problem(std::string("this face ") + (faceHasUvs ? "has" : "has no") +
                     " texture coordinates but the first face (line " + std::to_string(faceLines_.front()) + ") " +
                     (faceHasUvs ? "has none" : "has them"));
    cage_.faceSizes.push_back(static_cast<std::uint32_t>(tokens.size() - 1));
    faceLines_.push_back(line_);
    return {};
  }

  struct TagCounts {
    std::size_t ints = 0, floats = 0, strings = 0;
  };

  Result<TagCounts> parseTagCounts(std::string_view token) const {
    TagCounts counts;
    const std::size_t first = token.find('/');
    const std::size_t second = first == std::string_view::npos ? first : token.find('/', first + 1);
    if (second == std::string_view::npos || !parseNumber(token.substr(0, first), counts.ints) ||
        !parseNumber(token.substr(first + 1, second - first - 1), counts.floats) ||
        !parseNumber(token.substr(second + 1), counts.strings))
      return problem(quoted(token) + " should count the tag's arguments as ints/floats/strings");
    return counts;
  }

  Result<void> parseTag(const std::vector<std::string_view>& tokens) {
    if (tokens.size() < 3) return problem("a tag needs a name and an ints/floats/strings count");
    const std::string name(tokens[1]);
    auto counts = parseTagCounts(tokens[2]);
    if (!counts) return std::unexpected(counts.error());
    if (tokens.size() != 3 + counts->ints + counts->floats + counts->strings)
      return problem("tag '" + name + "' announces " + std::to_string(counts->ints + counts->floats + counts->strings) +
                     " arguments but has " + std::to_string(tokens.size() - 3));
    std::vector<std::uint32_t> ints(counts->ints);
    std::vector<float> floats(counts->floats);
    for (std::size_t i = 0; i < counts->ints; ++i)
      if (!parseNumber(tokens[3 + i], ints[i]))
        return problem(quoted(tokens[3 + i]) + " in tag '" + name + "' is not a vertex index (0-based)");
    for (std::size_t i = 0; i < counts->floats; ++i)
      if (!parseNumber(tokens[3 + counts->ints + i], floats[i]) || !std::isfinite(floats[i]))
        return problem(quoted(tokens[3 + counts->ints + i]) + " in tag '" + name + "' is not a finite number");

    if (name == "crease") {
      if (ints.size() < 2 || (floats.size() != 1 && floats.size() != ints.size() - 1))
        return problem("a crease tag needs a chain of at least 2 vertices and 1 sharpness, or one per edge");
      for (std::size_t i = 0; i + 1 < ints.size(); ++i) {
        cage_.creases.push_back({ints[i], ints[i + 1], floats.size() == 1 ? floats[0] : floats[i]});
        creaseLines_.push_back(line_);
      }
      return {};
    }
    if (name == "corner") {
      if (ints.empty() || (floats.size() != 1 && floats.size() != ints.size()))
        return problem("a corner tag needs at least 1 vertex and 1 sharpness, or one per vertex");
      for (std::size_t i = 0; i < ints.size(); ++i) {
        cage_.corners.push_back({ints[i], floats.size() == 1 ? floats[0] : floats[i]});
        cornerLines_.push_back(line_);
      }
      return {};
    }
    if (name == "interpolateboundary") {
      if (ints.size() != 1 || ints[0] > 2 || !floats.empty())
        return problem("interpolateboundary takes one int: 0 (none), 1 (edges only) or 2 (edges and corners)");
      cage_.boundary = ints[0] == 0   ? BoundaryInterpolation::kNone
                       : ints[0] == 1 ? BoundaryInterpolation::kEdgeOnly
                                      : BoundaryInterpolation::kEdgeAndCorner;
      return {};
    }
    return problem("unsupported tag '" + name + "'; this loader knows crease, corner and interpolateboundary");
  }

  Result<Cage> finish() {
    if (cage_.faceSizes.empty()) return problemAt(line_, "the file has no faces");
    if (auto found = findCageProblem(cage_)) {
      if (found->face) return problemAt(faceLines_[*found->face], found->message);
      if (found->crease) return problemAt(creaseLines_[*found->crease], found->message);
      if (found->corner) return problemAt(cornerLines_[*found->corner], found->message);
      return fail(std::string(source_) + ": " + found->message);
    }
    return std::move(cage_);
  }

  std::string_view source_;
  std::size_t line_ = 0;
  Cage cage_;
  bool firstFaceHasUvs_ = false;
  std::vector<std::size_t> faceLines_;
  std::vector<std::size_t> creaseLines_;
  std::vector<std::size_t> cornerLines_;
};

}  // namespace

Result<Cage> parseCageObj(std::string_view text, std::string_view sourceName) {
  return CageObjParser(sourceName).parse(text);
}

Result<Cage> loadCageObj(const std::filesystem::path& file) {
  std::ifstream stream(file, std::ios::binary);
  if (!stream) return fail(file.string() + ": cannot open the file for reading");
  std::ostringstream contents;
  contents << stream.rdbuf();
  if (stream.bad()) return fail(file.string() + ": reading the file failed");
  const std::string text = contents.str();
  return parseCageObj(text, file.string());
}

}  // namespace mane::subdiv
