// SPDX-License-Identifier: MIT
// Status / StatusOr: how every engine function reports failure without exceptions
// (Draco-style). Codes are stable; messages name the file/element and the problem.
#pragma once
#include <cassert>
#include <optional>
#include <string>
#include <utility>

namespace silk {

enum class StatusCode : int {
  kOk = 0,
  kInvalidArgument = 1,  // caller passed something unusable
  kIoError = 2,          // file cannot be opened / read / written
  kParseError = 3,       // malformed file content
  kUnsupported = 4,      // valid input, feature not supported
  kRefused = 5,          // tokenizer refusal (structure limits, non-manifold, mobius, ...)
  kLimitExceeded = 6,    // plausibility / resource limit
  kCancelled = 7,
  kInternal = 8,
};

const char* StatusCodeName(StatusCode c);

class [[nodiscard]] Status {
 public:
  Status() = default;
  Status(StatusCode code, std::string message) : code_(code), message_(std::move(message)) {}
  static Status Ok() { return Status(); }
  bool ok() const { return code_ == StatusCode::kOk; }
  StatusCode code() const { return code_; }
  const std::string& message() const { return message_; }
  // "parse error: <message>"
  std::string ToString() const;
  // Prepends context ("file.obj: ") to the message, keeping the code.
  Status WithContext(const std::string& prefix) const;

 private:
  StatusCode code_ = StatusCode::kOk;
  std::string message_;
};

inline Status InvalidArgument(std::string m) { return Status(StatusCode::kInvalidArgument, std::move(m)); }
inline Status IoError(std::string m) { return Status(StatusCode::kIoError, std::move(m)); }
inline Status ParseError(std::string m) { return Status(StatusCode::kParseError, std::move(m)); }
inline Status Unsupported(std::string m) { return Status(StatusCode::kUnsupported, std::move(m)); }
inline Status LimitExceeded(std::string m) { return Status(StatusCode::kLimitExceeded, std::move(m)); }
inline Status InternalError(std::string m) { return Status(StatusCode::kInternal, std::move(m)); }

template <typename T>
class [[nodiscard]] StatusOr {
 public:
  StatusOr(Status s) : status_(std::move(s)) { assert(!status_.ok()); }  // NOLINT
  StatusOr(T value) : value_(std::move(value)) {}                        // NOLINT
  bool ok() const { return status_.ok(); }
  const Status& status() const { return status_; }
  T& value() & { return *value_; }
  const T& value() const& { return *value_; }
  T&& value() && { return std::move(*value_); }
  T* operator->() { return &*value_; }
  const T* operator->() const { return &*value_; }
  T& operator*() & { return *value_; }
  const T& operator*() const& { return *value_; }

 private:
  Status status_;
  std::optional<T> value_;
};

#define SILK_RETURN_IF_ERROR(expr)               \
  do {                                           \
    ::silk::Status silk_status_ = (expr);        \
    if (!silk_status_.ok()) return silk_status_; \
  } while (0)

#define SILK_CONCAT_INNER(a, b) a##b
#define SILK_CONCAT(a, b) SILK_CONCAT_INNER(a, b)
#define SILK_ASSIGN_OR_RETURN(lhs, expr)                                                        \
  auto SILK_CONCAT(silk_sor_, __LINE__) = (expr);                                               \
  if (!SILK_CONCAT(silk_sor_, __LINE__).ok()) return SILK_CONCAT(silk_sor_, __LINE__).status(); \
  lhs = std::move(SILK_CONCAT(silk_sor_, __LINE__)).value()

}  // namespace silk
