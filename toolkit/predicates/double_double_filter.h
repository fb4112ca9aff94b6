// Intermediate filter stage of orient3d and insphere: the determinant evaluated in
// double-double arithmetic from the exact coordinate differences, with a proven forward
// error bound (toolkit/predicates/double_double.h for the arithmetic and the error rules,
// double_double_filter.cpp for the constants). It sits between Shewchuk's floating-point
// filter (stage A) and his adaptive stages B/C (predicates.cpp) and decides the
// near-degenerate cases whose determinant is not tiny against eps^2 times the permanent,
// e.g. every insphere test among points rounded onto a sphere.
//
// Declared outside predicates.cpp so that tests can check the stage on its own.
#pragma once

#include "toolkit/predicates/predicates.h"

namespace delmesh::predicates::detail {

/// orient3d(a,b,c,d) in the convention of predicates.h, if certain at double-double
/// precision: returns true and sets `out`; returns false (and leaves `out`) otherwise.
bool orient3d_double_double(const double* a, const double* b, const double* c, const double* d,
                            Sign& out);

/// insphere(a,b,c,d,e) in the convention of predicates.h, if certain at double-double
/// precision: returns true and sets `out`; returns false otherwise.
bool insphere_double_double(const double* a, const double* b, const double* c, const double* d,
                            const double* e, Sign& out);

}  // namespace delmesh::predicates::detail
