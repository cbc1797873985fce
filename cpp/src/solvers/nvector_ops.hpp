// Our own element-wise operations for SUNDIALS' serial vectors.
//
// Debian's SUNDIALS 6.4 libraries are built without optimization (-O0):
// their vector loops (linear sums, norms, the linear combinations of the
// Runge-Kutta stages and BDF predictors) cost 5 to 20 instructions per
// element and were a third of a BDF step on a long chain. The operations
// are a handful of one-line loops, so lagmb compiles its own with the rest
// of the library and sets them in each vector's table of operations; the
// vectors SUNDIALS clones from it inherit them.
#pragma once

#include <sundials/sundials_nvector.h>

namespace lagmb::sun {

/// Sets the serial vector v's element-wise and fused operations (linear
/// sum, scale, constant, product, quotient, abs, inverse, add constant, max
/// norm, weighted RMS norms, dot product, linear combination, scale-add
/// multi, vector-array sums) to lagmb's.
void use_compiled_vector_ops(N_Vector v);

}  // namespace lagmb::sun
