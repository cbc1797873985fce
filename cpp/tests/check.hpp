// The few checks the C++ unit tests need, header-only (no test framework to
// download: the machines building lagmb have Debian and PyPI packages only).
// A test file defines cases with TEST_CASE(name) { ... CHECK(...); ... } and
// ends with LAGMB_TEST_MAIN(); its program runs every case (or those named
// on its command line), prints each failed check with its file and line,
// and exits non-zero if any failed, which is what ctest reads.
#pragma once

#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

namespace lagmb_test {

struct Case {
  const char* name;
  void (*run)();
};

inline std::vector<Case>& cases() {
  static std::vector<Case> all;
  return all;
}

inline int& failed_checks() {
  static int n = 0;
  return n;
}

struct Register {
  Register(const char* name, void (*run)()) { cases().push_back({name, run}); }
};

inline bool report(bool ok, const std::string& what, const char* file, int line) {
  if (!ok) {
    ++failed_checks();
    std::printf("  %s:%d: failed: %s\n", file, line, what.c_str());
  }
  return ok;
}

/// |a - b| <= tol, with both values in the message when not.
inline bool near(double a, double b, double tol, const char* text, const char* file, int line) {
  const bool ok = std::abs(a - b) <= tol;  // (false for NaN)
  char values[160];
  std::snprintf(values, sizeof values, " (%.17g against %.17g, difference %.3g > %.3g)", a, b, std::abs(a - b), tol);
  return report(ok, std::string(text) + values, file, line);
}

/// Runs the cases named in argv (all without names); 0 if every check held
/// and no case threw.
inline int run(int argc, char** argv) {
  int failed_cases = 0, ran = 0;
  for (const Case& c : cases()) {
    bool chosen = argc <= 1;
    for (int k = 1; k < argc; ++k) chosen = chosen || std::strcmp(argv[k], c.name) == 0;
    if (!chosen) continue;
    ++ran;
    const int before = failed_checks();
    std::printf("%s\n", c.name);
    try {
      c.run();
    } catch (const std::exception& e) {
      report(false, std::string("threw: ") + e.what(), c.name, 0);
    }
    if (failed_checks() > before) ++failed_cases;
  }
  std::printf("%d of %d cases passed\n", ran - failed_cases, ran);
  return failed_cases == 0 && ran > 0 ? 0 : 1;
}

}  // namespace lagmb_test

#define TEST_CASE(name)                                                          \
  static void name();                                                            \
  static const lagmb_test::Register name##_registered(#name, &name);             \
  static void name()

#define CHECK(condition) lagmb_test::report(bool(condition), #condition, __FILE__, __LINE__)

#define CHECK_NEAR(a, b, tol) lagmb_test::near((a), (b), (tol), #a " == " #b, __FILE__, __LINE__)

/// `statement` throws Error whose what() contains `text`.
#define CHECK_THROWS(Error, statement, text)                                                          \
  do {                                                                                                \
    std::string lagmb_test_message = "no exception";                                                  \
    bool lagmb_test_ok = false;                                                                       \
    try {                                                                                             \
      statement;                                                                                      \
    } catch (const Error& e) {                                                                        \
      lagmb_test_message = e.what();                                                                  \
      lagmb_test_ok = lagmb_test_message.find(text) != std::string::npos;                             \
    } catch (const std::exception& e) {                                                               \
      lagmb_test_message = std::string("another exception: ") + e.what();                             \
    }                                                                                                 \
    lagmb_test::report(lagmb_test_ok,                                                                 \
                       std::string(#statement " throws " #Error " saying \"") + (text) + "\"; got: " + \
                           lagmb_test_message,                                                        \
                       __FILE__, __LINE__);                                                           \
  } while (false)

#define LAGMB_TEST_MAIN() \
  int main(int argc, char** argv) { return lagmb_test::run(argc, argv); }
