#pragma once
// The error type every module returns across its boundary (docs/design.md#errors-as-values).

#include <expected>
#include <string>
#include <utility>

namespace mane {

/// A recoverable failure, described for a person: which file or object, where, what was
/// expected. Messages are complete sentences without a trailing newline.
struct Error {
  std::string message;
};

template <class T>
using Result = std::expected<T, Error>;

/// Shorthand for `std::unexpected(Error{...})`.
inline std::unexpected<Error> fail(std::string message) {
  return std::unexpected(Error{std::move(message)});
}

}  // namespace mane
