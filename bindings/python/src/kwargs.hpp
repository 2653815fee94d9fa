// kwargs.hpp - the one keyword parser of the extension modules' vectorcall
// (METH_FASTCALL) functions: t_test, var_test and ks_test parse their own
// arguments because they are called in loops (pybind11's parser costs as
// much as a small test).
//
// The caller lists its parameters as (name, slot) pairs: positional ones in
// order, then keyword-only ones (a null name is a parameter this function
// does not have).  Each slot receives a borrowed reference to
// the argument given, or stays nullptr.  Errors are TypeErrors worded as
// Python's own.  Beside it, the integer argument both modules take (seeds,
// counts): to_u64.
//
// Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
#pragma once

#include <pybind11/pybind11.h>

#include <cstdint>
#include <initializer_list>
#include <string>

namespace mcs_kwargs {

struct Param {
    const char *name;
    PyObject **slot;
};

inline std::string repr_of(PyObject *o)
{
    return pybind11::repr(o).cast<std::string>();
}

// Fills the slots of `positional` from args[0..nargs) and the slot of each
// keyword in kwnames by name (positional parameters may also be given by
// keyword).  TypeError for too many positional arguments, an unknown
// keyword, or a parameter given twice.
inline void parse(const char *fname, PyObject *const *args, Py_ssize_t nargs, PyObject *kwnames,
                  std::initializer_list<Param> positional, std::initializer_list<Param> keywords)
{
    if (nargs > static_cast<Py_ssize_t>(positional.size())) {
        std::string names;
        for (const Param &p : positional)
            names += (names.empty() ? "" : ", ") + std::string(p.name);
        throw pybind11::type_error(std::string(fname) + "() takes at most " + std::to_string(positional.size()) +
                                   " positional arguments (" + names + "), " + std::to_string(nargs) + " given");
    }
    Py_ssize_t i = 0;
    for (const Param &p : positional)
        if (i < nargs)
            *p.slot = args[i++];
    Py_ssize_t nk = kwnames ? PyTuple_GET_SIZE(kwnames) : 0;
    for (Py_ssize_t k = 0; k < nk; k++) {
        PyObject *name = PyTuple_GET_ITEM(kwnames, k);
        PyObject **slot = nullptr;
        for (const Param &p : keywords)
            if (p.name && PyUnicode_CompareWithASCIIString(name, p.name) == 0) {
                slot = p.slot;
                break;
            }
        if (!slot)
            for (const Param &p : positional)
                if (PyUnicode_CompareWithASCIIString(name, p.name) == 0) {
                    slot = p.slot;
                    break;
                }
        if (!slot)
            throw pybind11::type_error(std::string(fname) + "() got an unexpected keyword argument " +
                                       repr_of(name));
        if (*slot)
            throw pybind11::type_error(std::string(fname) + "() got multiple values for argument " +
                                       repr_of(name));
        *slot = args[nargs + k];
    }
}

// A Python int in [0, 2^64) (NumPy integers too; not bool): TypeError for
// other types, invalid(message) (which throws the module's own
// InvalidArgumentError) for negative or too large values.
template <typename Invalid> uint64_t to_u64(PyObject *o, const char *name, Invalid invalid)
{
    if (PyBool_Check(o) || !PyIndex_Check(o))
        throw pybind11::type_error(std::string(name) + " must be an int, got " + repr_of(o));
    pybind11::object i = pybind11::reinterpret_steal<pybind11::object>(PyNumber_Index(o));
    if (!i)
        throw pybind11::error_already_set();
    const std::string range = std::string(name) + " must be a non-negative int below 2**64, got ";
    if (PyObject_RichCompareBool(i.ptr(), pybind11::int_(0).ptr(), Py_LT) == 1)
        invalid(range + repr_of(o));
    unsigned long long v = PyLong_AsUnsignedLongLong(i.ptr());
    if (v == static_cast<unsigned long long>(-1) && PyErr_Occurred()) {
        PyErr_Clear();
        invalid(range + repr_of(o));
    }
    return static_cast<uint64_t>(v);
}

} // namespace mcs_kwargs
