"""lagmb's own operations on SUNDIALS vectors.

Debian's SUNDIALS 6.4 is compiled without optimization, so lagmb sets its
own element-wise and fused vector operations (cpp/src/solvers/nvector_ops.cpp) in
every vector the integrators use. They must compute what SUNDIALS' serial
operations compute, including when the output is also an input (a linear
combination written over its second vector: an early version overwrote it
first, which still ran but changed every BDF step on a 100,000-link chain).
"""

import pytest

from lagmb import _core

OPERATIONS = {
    "linear_sum", "constant", "product", "quotient", "scale", "abs", "inverse", "add_constant",
    "max_norm", "wrms_norm", "wrms_norm_mask", "dot", "linear_combination", "scale_add_multi",
    "linear_sum_vector_array", "scale_vector_array",
}


@pytest.mark.parametrize("n", [1, 7, 256, 1000])
def test_every_vector_operation_agrees_with_sundials_to_rounding(n):
    differences = _core.compare_vector_operations(n, seed=n)
    assert set(differences) == OPERATIONS
    for name, d in differences.items():
        assert d <= 1e-14, f"{name}: relative difference {d:g}"
