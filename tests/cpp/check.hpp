// Minimal assertions for the C++ tests: each failure is printed; main returns the failure count.
#pragma once

#include <cmath>
#include <iostream>
#include <string>

namespace test {
inline int failures = 0;

inline void near(const std::string& what, double got, double expected, double tolerance) {
  if (!(std::abs(got - expected) <= tolerance)) {
    ++failures;
    std::cerr.precision(15);
    std::cerr << "FAIL " << what << ": got " << got << ", expected " << expected << " +- "
              << tolerance << "\n";
  }
}

inline void that(const std::string& what, bool ok) {
  if (!ok) {
    ++failures;
    std::cerr << "FAIL " << what << "\n";
  }
}

template <class F>
void throws(const std::string& what, F&& f, const std::string& must_mention) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    if (std::string(e.what()).find(must_mention) == std::string::npos) {
      ++failures;
      std::cerr << "FAIL " << what << ": message '" << e.what() << "' does not name "
                << must_mention << "\n";
    }
    return;
  }
  ++failures;
  std::cerr << "FAIL " << what << ": no std::invalid_argument thrown\n";
}

inline int report(const char* name) {
  std::cout << name << ": " << (failures == 0 ? "ok" : "FAILED") << " (" << failures
            << " failures)\n";
  return failures == 0 ? 0 : 1;
}
}  // namespace test
