#pragma once
// Strict, path-tracking reads from nlohmann::json for the scene parser. Private to scenes/.
// Failures throw FieldError, which loadScene turns into an Error at its boundary: the
// parser stays a straight list of fields instead of a ladder of early returns.

#include <cmath>
#include <set>
#include <string>
#include <utility>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

namespace mane::scenes::detail {

/// A validation failure at JSON field `path` (e.g. "lights[1].direction").
struct FieldError {
  std::string path;
  std::string message;
};

inline std::string childPath(const std::string& parent, const std::string& key) {
  return parent.empty() ? key : parent + "." + key;
}

inline std::string indexPath(const std::string& parent, std::size_t index) {
  return parent + "[" + std::to_string(index) + "]";
}

inline std::string got(const nlohmann::json& json) {
  if (json.is_number()) return ", got a number";
  if (json.is_string()) return ", got a string";
  if (json.is_array()) return ", got an array";
  if (json.is_object()) return ", got an object";
  if (json.is_boolean()) return ", got a boolean";
  return ", got null";
}

template <class T>
T read(const nlohmann::json& json, const std::string& path);

template <>
inline float read<float>(const nlohmann::json& json, const std::string& path) {
  if (!json.is_number()) throw FieldError{path, "expected a number" + got(json)};
  const double value = json.get<double>();
  // 1e39 is a finite double but overflows float to infinity.
  if (!std::isfinite(value) || !std::isfinite(static_cast<float>(value))) {
    throw FieldError{path, "expected a finite number within float range (|x| < 3.4e38)"};
  }
  return static_cast<float>(value);
}

template <>
inline int read<int>(const nlohmann::json& json, const std::string& path) {
  if (!json.is_number_integer()) {
    throw FieldError{path, "expected an integer" + (json.is_number() ? std::string(", got a "
                                                                                   "fraction")
                                                                     : got(json))};
  }
  const auto value = json.get<long long>();
  if (value < -(1LL << 31) || value >= (1LL << 31)) {
    throw FieldError{path, "integer out of range"};
  }
  return static_cast<int>(value);
}

template <>
inline bool read<bool>(const nlohmann::json& json, const std::string& path) {
  if (!json.is_boolean()) throw FieldError{path, "expected true or false" + got(json)};
  return json.get<bool>();
}

template <>
inline std::string read<std::string>(const nlohmann::json& json, const std::string& path) {
  if (!json.is_string()) throw FieldError{path, "expected a string" + got(json)};
  return json.get<std::string>();
}

template <>
inline glm::vec3 read<glm::vec3>(const nlohmann::json& json, const std::string& path) {
  if (!json.is_array() || json.size() != 3) {
    throw FieldError{path, "expected an array of 3 numbers" +
                               (json.is_array() ? ", got " + std::to_string(json.size()) + " elements" : got(json))};
  }
  glm::vec3 value;
  for (int i = 0; i < 3; ++i) {
    value[i] = read<float>(json[static_cast<std::size_t>(i)], indexPath(path, static_cast<std::size_t>(i)));
  }
  return value;
}

/// The fields of one JSON object. Every field the parser asks for is "known"; `finish`
/// rejects any other field, listing the known ones, so a typo cannot pass silently.
class ObjectFields {
public:
  ObjectFields(const nlohmann::json& json, std::string path) : json_(json), path_(std::move(path)) {
    if (!json_.is_object()) {
      throw FieldError{path_.empty() ? "(top level)" : path_, "expected an object" + got(json_)};
    }
  }

  [[nodiscard]] const std::string& path() const { return path_; }
  [[nodiscard]] std::string child(const std::string& key) const { return childPath(path_, key); }

  /// The field's JSON, or nullptr when absent; marks the key as known either way.
  const nlohmann::json* take(const std::string& key) {
    known_.insert(key);
    const auto it = json_.find(key);
    return it == json_.end() ? nullptr : &*it;
  }

  template <class T>
  T required(const std::string& key) {
    const nlohmann::json* value = take(key);
    if (!value) throw FieldError{child(key), "required field is missing"};
    return read<T>(*value, child(key));
  }

  template <class T>
  T optional(const std::string& key, T fallback) {
    const nlohmann::json* value = take(key);
    return value ? read<T>(*value, child(key)) : std::move(fallback);
  }

  /// An array field (empty json array when absent and not required).
  const nlohmann::json& array(const std::string& key, bool isRequired) {
    static const nlohmann::json kEmpty = nlohmann::json::array();
    const nlohmann::json* value = take(key);
    if (!value) {
      if (isRequired) throw FieldError{child(key), "required field is missing"};
      return kEmpty;
    }
    if (!value->is_array()) throw FieldError{child(key), "expected an array" + got(*value)};
    return *value;
  }

  /// Throws for the first field that no `take` asked about.
  void finish() const {
    for (const auto& item : json_.items()) {
      if (known_.contains(item.key())) continue;
      std::string list;
      for (const std::string& key : known_) list += (list.empty() ? "" : ", ") + key;
      throw FieldError{child(item.key()), "unknown field (expected one of: " + list + ")"};
    }
  }

private:
  const nlohmann::json& json_;
  std::string path_;
  std::set<std::string> known_;
};

inline void require(bool condition, const std::string& path, const std::string& message) {
  if (!condition) throw FieldError{path, message};
}

/// Each element of the array `key` (optional; none when absent) parsed by `parse(json, path)`.
template <class T, class Parse>
std::vector<T> parseList(ObjectFields& fields, const std::string& key, Parse parse) {
  std::vector<T> out;
  const nlohmann::json& items = fields.array(key, false);
  for (std::size_t i = 0; i < items.size(); ++i) {
    out.push_back(parse(items[i], indexPath(fields.child(key), i)));
  }
  return out;
}

}  // namespace mane::scenes::detail
