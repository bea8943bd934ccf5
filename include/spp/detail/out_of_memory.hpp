#pragma once
// std::bad_alloc that says what was too large: the CLI prints its what(), pybind11 raises MemoryError with it. A bare
// std::bad_alloc says only "std::bad_alloc", which names neither the object nor its size.

#include <cstdio>
#include <new>
#include <string>
#include <utility>

namespace spp::detail {

class OutOfMemory : public std::bad_alloc {
 public:
  explicit OutOfMemory(std::string message) : message_(std::move(message)) {}
  const char* what() const noexcept override { return message_.c_str(); }

 private:
  std::string message_;
};

/// "a 200000 x 200000 matrix of doubles (320 GB)": what an allocation of rows x cols doubles asks for.
inline std::string dense_size(double rows, double cols) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "a %.0f x %.0f matrix of doubles (%.4g GB)", rows, cols, rows * cols * 8e-9);
  return buf;
}

/// Runs f; a std::bad_alloc from it becomes OutOfMemory("out of memory: " + what). An OutOfMemory thrown deeper down
/// (naming a smaller part) passes through unchanged.
template <typename F>
decltype(auto) naming_allocation(const std::string& what, F&& f) {
  try {
    return std::forward<F>(f)();
  } catch (const OutOfMemory&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw OutOfMemory("out of memory: " + what);
  }
}

}  // namespace spp::detail
