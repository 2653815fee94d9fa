// real_array.hpp - the one check on every array argument of mcstat._core
// and mcstat._estimators (header-only: they are separate modules).
//
// Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>

namespace mcs {

namespace py = pybind11;

// obj as NumPy reads it, refused when its values are not real numbers:
// casting complex to float64 drops the imaginary part (NumPy only warns),
// datetime64/timedelta64 become counts of their unit, and object or string
// arrays are not numbers at all.  bool and integer arrays are accepted.
inline py::array real_array(py::handle obj, const char *name)
{
    py::array a = py::array::ensure(obj);
    if (!a) { // pybind11 swallowed NumPy's error: let NumPy raise it again
        py::module_::import("numpy").attr("asarray")(obj);
        throw py::type_error(std::string(name) + ": cannot convert " + py::repr(obj).cast<std::string>() + " to an array");
    }
    char kind = a.dtype().kind();
    if (kind == 'f' || kind == 'i' || kind == 'u' || kind == 'b')
        return a;
    std::string dt = py::str(a.dtype()).cast<std::string>(), why;
    switch (kind) {
    case 'c': why = "complex values would lose their imaginary part; pass .real, .imag or abs() explicitly"; break;
    case 'M':
    case 'm': why = "dates and durations are not plain numbers; convert them, e.g. x / np.timedelta64(1, 's')"; break;
    case 'O': why = "an object array (None, Decimal, mixed types...) is not an array of numbers; convert it "
                    "with np.asarray(x, dtype=float) first"; break;
    case 'S':
    case 'U': why = "strings are not numbers"; break;
    default: why = "the values are not real numbers"; break;
    }
    throw py::type_error(std::string(name) + " must hold real numbers (float, int or bool), got dtype " + dt + ": " +
                         why);
}

} // namespace mcs
