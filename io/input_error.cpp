#include "io/input_error.hpp"

namespace msislab::io {

void fail_at(const std::string& file, std::size_t line, const std::string& what) {
  throw InputError(file + ":" + std::to_string(line) + ": " + what);
}

void fail_file(const std::string& file, const std::string& what) {
  throw InputError(file + ": " + what);
}

}  // namespace msislab::io
