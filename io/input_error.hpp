// The one error type for bad input. Its message is the single line a user sees:
// "FILE:LINE: what is wrong" or "FILE: key 'a.b': what is wrong". The CLI prints it and exits 2.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

namespace msislab::io {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Throws InputError("file:line: what").
[[noreturn]] void fail_at(const std::string& file, std::size_t line, const std::string& what);

/// Throws InputError("file: what").
[[noreturn]] void fail_file(const std::string& file, const std::string& what);

}  // namespace msislab::io
