#pragma once
// Errors as values (vk-bootstrap style): set-up and loading code returns a
// Result<T> instead of throwing, so callers decide how to report the failure.
#include <cassert>
#include <cstdint>
#include <string>
#include <utility>
#include <variant>

namespace eng {

struct Error {
  std::string message;  // one readable line; names the file and the problem
  int32_t code = 0;     // VkResult for Vulkan failures, 0 otherwise
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
  Error error_;
  bool failed_ = false;
};

inline Error makeError(std::string message, int32_t code = 0) { return Error{std::move(message), code}; }

}  // namespace eng
