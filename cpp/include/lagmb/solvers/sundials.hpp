// What lagmb takes from SUNDIALS, as users may ask about it.
#pragma once

#include <map>
#include <string>

namespace lagmb {

/// Version of the SUNDIALS library lagmb was built with, e.g. "6.4.1".
std::string sundials_version();

/// lagmb's own operations on SUNDIALS serial vectors (they replace the
/// library's, which Debian builds without optimization) against SUNDIALS'
/// serial ones, on random vectors of length n, with the aliasings SUNDIALS
/// uses (z = x or y in a linear sum; z = X_0 or X_1 in a linear
/// combination; Z = Y in a scale-add): the largest difference per
/// operation, relative to the largest entry.
std::map<std::string, double> compare_vector_operations(int n, unsigned seed);

}  // namespace lagmb
