#pragma once
// Errors as values (vk-bootstrap style): set-up and loading code returns a
// Result<T> instead of throwing, so callers decide how to report the failure.
// Every error has a kind a caller can branch on (retry, ask for another file,
// report a bug) and a message for a person.
#include <cassert>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <variant>

namespace eng {

enum class ErrorKind : uint8_t {
  NotFound,         // a file, or a name the caller asked for (target, parameter, preset, node), does not exist
  Io,               // the file exists but cannot be read, listed or written (permissions, a folder, disk full)
  Malformed,        // the content breaks its format: syntax, an index out of range, mismatched counts, NaN
  Unsupported,      // well-formed, but uses a version, extension or feature this build does not implement
  TooLarge,         // over a size, count or nesting limit (set against hostile input) or a format's own limit
  InvalidArgument,  // the caller broke a precondition: mismatched span sizes, a negative dt, a null model
  Device,           // the GPU, driver, Vulkan loader or window system failed or lacks a capability
};

// The kind's name, e.g. "not found", for logs and tests.
constexpr std::string_view errorKindName(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::NotFound: return "not found";
    case ErrorKind::Io: return "i/o";
    case ErrorKind::Malformed: return "malformed";
    case ErrorKind::Unsupported: return "unsupported";
    case ErrorKind::TooLarge: return "too large";
    case ErrorKind::InvalidArgument: return "invalid argument";
    case ErrorKind::Device: return "device";
  }
  return "?";
}

struct Error {
  ErrorKind kind;       // what went wrong, for the caller to branch on
  std::string message;  // one readable line; names the file and the problem
  int32_t code = 0;     // VkResult for Vulkan failures, 0 otherwise

  // The same failure seen from an outer layer: `context` (e.g. "face.glb: ")
  // goes in front of the message; the kind and code stay.
  Error prefixed(std::string_view context) const { return Error{kind, std::string(context) + message, code}; }
};

template <class T>
class [[nodiscard]] Result {
 public:
  Result(T value) : v_(std::move(value)) {}
  Result(Error error) : v_(std::move(error)) {}

  bool ok() const { return v_.index() == 0; }
  explicit operator bool() const { return ok(); }

  T& value() & { assert(ok()); return std::get<0>(v_); }
  const T& value() const& { assert(ok()); return std::get<0>(v_); }
  T&& value() && { assert(ok()); return std::get<0>(std::move(v_)); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }

  const Error& error() const { assert(!ok()); return std::get<1>(v_); }

 private:
  std::variant<T, Error> v_;
};

template <>
class [[nodiscard]] Result<void> {
 public:
  Result() = default;
  Result(Error error) : error_(std::move(error)), failed_(true) {}
  bool ok() const { return !failed_; }
  explicit operator bool() const { return ok(); }
  const Error& error() const { assert(failed_); return error_; }

 private:
  Error error_{};  // value-initialised: no indeterminate kind while ok()
  bool failed_ = false;
};

inline Error makeError(ErrorKind kind, std::string message, int32_t code = 0) {
  return Error{kind, std::move(message), code};
}

}  // namespace eng

// Returns the error of a failed eng::Result from the enclosing function.
#define ENG_TRY(expr)                                      \
  do {                                                     \
    if (auto&& eng_try_result_ = (expr); !eng_try_result_) \
      return eng_try_result_.error();                      \
  } while (0)

// The value of an eng::Result<T>, or its error returned from the enclosing
// function: `float w = ENG_TRY_VALUE(node.number());`. A statement expression
// (GCC and Clang, the compilers this project builds with) so that readers of
// nested data stay one line per field instead of three.
// Its `return` leaves the enclosing full-expression without destroying what
// that expression already built: never put it after a non-trivial part of
// one aggregate or call (Foo{.name = ENG_TRY_VALUE(a), .x = ENG_TRY_VALUE(b)}
// leaks `name` when b fails; the graph fuzzer found one). One read per
// statement, or only one read in the expression (other parts read before).
#define ENG_TRY_VALUE(expr)                                  \
  ({                                                         \
    auto eng_try_value_ = (expr);                            \
    if (!eng_try_value_) return eng_try_value_.error();      \
    std::move(eng_try_value_).value();                       \
  })
