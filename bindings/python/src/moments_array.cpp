// moments_array.cpp - mcstat.MomentsArray: one accumulator per pixel (the
// render-farm case), over libmcstat's mcstat_moments_*_rows.
//
// The accumulators live in one std::vector<mcstat_moments> in C order of
// `shape`.  Every operation that can fail checks its input first and
// touches the accumulators only on success, as Moments.push does.
//
// Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
#include "common.hpp"
#include "threads.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <thread>
#include <vector>

namespace mcs {

namespace {

using carray = py::array_t<double, py::array::c_style | py::array::forcecast>;

std::string shape_str(const std::vector<py::ssize_t> &s)
{
    std::string out = "(";
    for (size_t k = 0; k < s.size(); k++)
        out += std::to_string(s[k]) + (k + 1 < s.size() ? ", " : (s.size() == 1 ? "," : ""));
    return out + ")";
}

// One dimension: an int (or NumPy integer), OverflowError naming `shape`
// beyond Py_ssize_t.
py::ssize_t dimension(py::handle d, py::handle shape)
{
    if (!PyLong_Check(d.ptr()) && !py::isinstance(d, py::module_::import("numpy").attr("integer")))
        throw py::type_error("shape must be an int or a tuple of ints, got " + repr(shape.ptr()));
    py::object i = py::reinterpret_steal<py::object>(PyNumber_Index(d.ptr()));
    if (!i)
        throw py::error_already_set();
    Py_ssize_t v = PyLong_AsSsize_t(i.ptr());
    if (v == -1 && PyErr_Occurred()) {
        PyErr_Clear();
        PyErr_SetString(PyExc_OverflowError, ("shape " + repr(shape.ptr()) + ": dimension " + repr(d.ptr()) +
                                              " is too large").c_str());
        throw py::error_already_set();
    }
    return v;
}

std::vector<py::ssize_t> parse_shape(py::handle shape)
{
    std::vector<py::ssize_t> s;
    if (PyLong_Check(shape.ptr())) {
        s.push_back(dimension(shape, shape));
    } else {
        for (py::handle d : py::iter(shape))
            s.push_back(dimension(d, shape));
    }
    for (auto d : s)
        if (d < 0)
            throw_invalid("shape must not have negative dimensions, got " + shape_str(s));
    return s;
}

// The number of pixels, refused (naming the shape) when the accumulators'
// bytes would not fit in memory's address range: unchecked, (2**32, 2**32)
// wrapped to 0 pixels and indexing read out of bounds.
size_t count_of(const std::vector<py::ssize_t> &s)
{
    for (auto d : s)
        if (d == 0)
            return 0;
    const size_t limit = static_cast<size_t>(PY_SSIZE_T_MAX) / sizeof(mcstat_moments);
    size_t n = 1;
    for (auto d : s) {
        if (static_cast<size_t>(d) > limit / n)
            throw_invalid("shape " + shape_str(s) + " has too many pixels: their accumulators would take more "
                          "than " + std::to_string(PY_SSIZE_T_MAX) + " bytes");
        n *= static_cast<size_t>(d);
    }
    return n;
}

bool parse_omit(const std::string &nan_policy)
{
    if (nan_policy == "raise")
        return false;
    if (nan_policy == "omit")
        return true;
    throw_invalid("nan_policy must be 'raise' or 'omit', got '" + nan_policy + "'");
}

// Rows [begin, end) on worker threads (disjoint ranges, as libmcstat
// allows), at least 4096 rows per thread.
template <typename F> void parallel_rows(size_t rows, F f)
{
    mcs_threads::split_ranges(rows, static_cast<size_t>(num_threads()), 4096, [&f](size_t b, size_t e) {
        f(b, e);
        return 0;
    });
}

// The pixels' values as (pixels, k) C-contiguous rows: one image (shape ==
// the array's shape, k = 1) or a stack of k images (shape (k,) + shape).
carray pixel_rows(const MomentsArray &s, py::handle images, size_t *k)
{
    py::module_ np = py::module_::import("numpy");
    py::array a = as_float_array(images, "images");
    size_t nd = static_cast<size_t>(a.ndim()), sd = s.shape.size();
    std::vector<py::ssize_t> got(a.shape(), a.shape() + nd);
    if (nd == sd && got == s.shape) {
        *k = 1;
        return carray::ensure(a.attr("reshape")(py::make_tuple(static_cast<py::ssize_t>(s.m.size()), 1)));
    }
    if (nd == sd + 1 && std::vector<py::ssize_t>(got.begin() + 1, got.end()) == s.shape) {
        *k = static_cast<size_t>(got[0]);
        py::object flat = a.attr("reshape")(py::make_tuple(got[0], static_cast<py::ssize_t>(s.m.size())));
        return carray::ensure(np.attr("ascontiguousarray")(flat.attr("T")));
    }
    throw_invalid("push() takes one image of shape " + shape_str(s.shape) + " or a stack of shape (k, " +
                  shape_str(s.shape).substr(1) + ", got shape " + shape_str(got));
}

void push(MomentsArray &s, py::handle images, bool omit)
{
    if (images.is_none())
        throw py::type_error("MomentsArray.push() needs an image or a stack of images, not None");
    size_t k;
    carray rows = pixel_rows(s, images, &k);
    const double *x = rows.data();
    size_t P = s.m.size();
    // The values are checked first (one pass), so that add_rows cannot fail
    // and the accumulators change only on success, as Moments.push does,
    // without a scratch copy of the accumulators.
    size_t bad = 0, where = 0;
    {
        py::gil_scoped_release nogil;
        for (size_t i = 0; i < P * k; i++) {
            if (!std::isfinite(x[i]) && !(omit && std::isnan(x[i])) && !bad++)
                where = i / k;
        }
    }
    if (bad)
        throw_status(MCSTAT_ENONFINITE, std::to_string(bad) + " value(s), the first at flat pixel index " +
                                            std::to_string(where) + "; the accumulators are unchanged");
    // Nor may a count pass 2**64 - 1 (add_rows would refuse that pixel alone).
    for (size_t i = 0; i < P; i++) {
        if (s.m[i].n <= UINT64_MAX - k)
            continue;
        uint64_t add = 0;
        for (size_t j = 0; j < k; j++)
            add += !std::isnan(x[i * k + j]);
        if (add > UINT64_MAX - s.m[i].n)
            throw_status(MCSTAT_ETOOBIG, "pixel at flat index " + std::to_string(i) + " would count more than "
                                         "2**64 - 1 values; the accumulators are unchanged");
    }
    std::atomic<int> first{MCSTAT_OK};
    {
        py::gil_scoped_release nogil;
        parallel_rows(P, [&](size_t b, size_t e) {
            int r = mcstat_moments_add_rows(s.m.data() + b, e - b, x + b * k, k, k,
                                            omit ? MCSTAT_ROWS_OMIT_NAN : 0u, nullptr);
            int ok = MCSTAT_OK;
            if (r)
                first.compare_exchange_strong(ok, r);
        });
    }
    if (first.load()) // not reached: the values and the accumulators were checked
        throw_status(first.load());
}

void check_same_shape(const MomentsArray &a, const MomentsArray &b, const char *what)
{
    if (a.shape != b.shape)
        throw_invalid(std::string(what) + ": shapes differ, " + shape_str(a.shape) + " and " + shape_str(b.shape));
}

void merge(MomentsArray &a, const MomentsArray &b)
{
    check_same_shape(a, b, "merge");
    int st;
    {
        py::gil_scoped_release nogil;
        st = mcstat_moments_merge_rows(a.m.data(), b.m.data(), a.m.size());
    }
    if (st)
        throw_status(st, "the accumulators are unchanged");
}

py::bytes to_bytes(const MomentsArray &s)
{
    size_t size = s.m.size() * MCSTAT_MOMENTS_BYTES;
    std::string buf(size, '\0');
    int st = mcstat_moments_to_bytes_rows(s.m.data(), s.m.size(), reinterpret_cast<unsigned char *>(&buf[0]), size);
    if (st)
        throw_status(st);
    return py::bytes(buf);
}

MomentsArray from_bytes(py::handle data, py::handle shape)
{
    Py_buffer view;
    if (PyObject_GetBuffer(data.ptr(), &view, PyBUF_SIMPLE) != 0)
        throw py::error_already_set();
    size_t len = static_cast<size_t>(view.len);
    MomentsArray out;
    try {
        if (shape.is_none())
            out.shape = {static_cast<py::ssize_t>(len / MCSTAT_MOMENTS_BYTES)};
        else
            out.shape = parse_shape(shape);
    } catch (...) {
        PyBuffer_Release(&view);
        throw;
    }
    size_t P;
    try {
        P = count_of(out.shape);
    } catch (...) {
        PyBuffer_Release(&view);
        throw;
    }
    // The length is checked before allocating: 3 bytes for shape (10**7,)
    // used to allocate 1.28 GB first.  P * 96 < P * 128 fits (count_of).
    if (len != P * MCSTAT_MOMENTS_BYTES) {
        PyBuffer_Release(&view);
        char detail[200];
        std::snprintf(detail, sizeof detail, "%zu bytes given; %zu accumulators of %u bytes (shape %s) are %zu", len,
                      P, MCSTAT_MOMENTS_BYTES, shape_str(out.shape).c_str(), P * MCSTAT_MOMENTS_BYTES);
        throw_status(MCSTAT_ECORRUPT, detail);
    }
    try {
        out.m.resize(P);
    } catch (...) {
        PyBuffer_Release(&view);
        throw;
    }
    int st = mcstat_moments_from_bytes_rows(static_cast<const unsigned char *>(view.buf), len, P, out.m.data());
    PyBuffer_Release(&view);
    if (st)
        throw_status(st);
    return out;
}

// A per-pixel quantity as an array of the accumulator's shape.
template <typename T, typename F> py::array_t<T> field(const MomentsArray &s, F f)
{
    py::array_t<T> out(s.shape);
    T *p = out.mutable_data();
    for (size_t i = 0; i < s.m.size(); i++)
        p[i] = f(s.m[i]);
    return out;
}

size_t flat_index(const MomentsArray &s, py::handle index)
{
    py::tuple idx = py::isinstance<py::tuple>(index) ? py::reinterpret_borrow<py::tuple>(index) : py::make_tuple(index);
    if (idx.size() != s.shape.size())
        throw py::index_error("index one pixel with " + std::to_string(s.shape.size()) + " integers, got " +
                              repr(index.ptr()));
    size_t flat = 0;
    for (size_t d = 0; d < s.shape.size(); d++) {
        py::handle v = idx[d];
        if (!PyLong_Check(v.ptr()) && !py::isinstance(v, py::module_::import("numpy").attr("integer")))
            throw py::index_error("index one pixel with integers, got " + repr(index.ptr()));
        py::ssize_t i = v.cast<py::ssize_t>();
        if (i < 0)
            i += s.shape[d];
        if (i < 0 || i >= s.shape[d])
            throw py::index_error("index " + repr(index.ptr()) + " is out of bounds for shape " + shape_str(s.shape));
        flat = flat * static_cast<size_t>(s.shape[d]) + static_cast<size_t>(i);
    }
    return flat;
}

} // namespace

const MomentsArray *as_moments_array(py::handle obj)
{
    static py::handle type = py::type::of<MomentsArray>();
    if (!PyObject_TypeCheck(obj.ptr(), reinterpret_cast<PyTypeObject *>(type.ptr())))
        return nullptr;
    return &obj.cast<const MomentsArray &>();
}

py::object test_moments_array(const TestArgs &a, py::handle x, py::handle y)
{
    bool two = a.kind == Kind::T2 || a.kind == Kind::V2 || a.kind == Kind::T2P;
    const MomentsArray *ax = as_moments_array(x), *ay = two ? as_moments_array(y) : nullptr;
    const MomentsArray *shaped = ax ? ax : ay;
    // A single Moments beside an array is compared with every pixel.
    std::vector<mcstat_moments> bx, by;
    auto side = [&](const MomentsArray *arr, py::handle obj, std::vector<mcstat_moments> &buf,
                    const char *name) -> const mcstat_moments * {
        if (arr) {
            if (arr->shape != shaped->shape)
                throw_invalid("x and y must be MomentsArrays of the same shape, got " + shape_str(shaped->shape) +
                              " and " + shape_str(arr->shape));
            return arr->m.data();
        }
        const mcstat_moments *one = as_moments(obj);
        if (!one)
            throw_invalid(std::string(name) + " must be an mcstat.MomentsArray or an mcstat.Moments when the "
                          "other sample is a MomentsArray, got " + repr(obj.ptr()) +
                          " (push arrays into a MomentsArray first)");
        buf.assign(shaped->m.size(), *one);
        return buf.data();
    };
    const mcstat_moments *px = side(ax, x, bx, "x");
    const mcstat_moments *py_ = two ? side(ay, y, by, "y") : nullptr;
    return run_moments_rows(a, px, py_, shaped->m.size(), shaped->shape);
}

void register_moments_array(py::module_ &mod)
{
    py::class_<MomentsArray>(mod, "MomentsArray", R"doc(
One streaming accumulator per pixel: an array of `Moments` (libmcstat's
``mcstat_moments_*_rows``), for render farms and other per-pixel Monte
Carlo estimates gathered on many threads, processes or machines.

Push images (one value per pixel) or stacks of images as they are
rendered, ship the array as bytes or by pickle (Dask, multiprocessing),
merge arrays element-wise, and pass the array to `t_test` or `var_test`
for one test per pixel (a `BatchResult` of arrays of this shape).

Pixel ``p`` is bit for bit the `Moments` that received the same pushes of
that pixel's values; pushing batches A then B on one machine equals
pushing them on two machines and merging in that order, bit for bit.

Parameters
----------
shape : int or tuple of ints
    The image's shape (any number of dimensions).

Examples
--------
>>> acc = mcstat.MomentsArray((48, 64))
>>> acc.push(stack)                  # stack.shape == (k, 48, 64)
>>> acc.merge(other)                 # from another worker
>>> r = mcstat.t_test(acc, mu=exact_image_mean)   # exact: a float
>>> r.reject.shape
(48, 64)
)doc")
        .def(py::init([](py::handle shape) {
                 MomentsArray s;
                 s.shape = parse_shape(shape);
                 s.m.resize(count_of(s.shape));
                 mcstat_moments_init_rows(s.m.data(), s.m.size());
                 return s;
             }),
             py::arg("shape"))
        .def(
            "push",
            [](py::object self, py::handle images, const std::string &nan_policy) {
                push(self.cast<MomentsArray &>(), images, parse_omit(nan_policy));
                return self;
            },
            py::arg("images"), py::kw_only(), py::arg("nan_policy") = "raise",
            R"doc(Adds one image (shape == self.shape) or a stack of k images (shape (k,) + self.shape); returns self.

Raises `NonFiniteError` (every accumulator unchanged) for infinite values
and, unless ``nan_policy="omit"``, for NaN; `InvalidArgumentError` for
another shape.)doc")
        .def(
            "merge",
            [](py::object self, const MomentsArray &other) {
                merge(self.cast<MomentsArray &>(), other);
                return self;
            },
            py::arg("other"), "Merges `other` (same shape) into this array pixel by pixel; returns self.")
        .def("__iadd__", [](py::object self, const MomentsArray &other) {
            merge(self.cast<MomentsArray &>(), other);
            return self;
        })
        .def("__add__", [](const MomentsArray &a, const MomentsArray &b) {
            MomentsArray out = a;
            merge(out, b);
            return out;
        })
        .def_property_readonly("shape", [](const MomentsArray &s) {
            py::tuple t(s.shape.size());
            for (size_t d = 0; d < s.shape.size(); d++)
                t[d] = py::int_(s.shape[d]);
            return t;
        }, "The image's shape.")
        .def_property_readonly("size", [](const MomentsArray &s) { return s.m.size(); }, "Number of pixels.")
        .def_property_readonly("ndim", [](const MomentsArray &s) { return s.shape.size(); })
        .def_property_readonly("n", [](const MomentsArray &s) {
            return field<int64_t>(s, [](const mcstat_moments &m) { return static_cast<int64_t>(m.n); });
        }, "Values per pixel (int64 array).")
        .def_property_readonly("mean", [](const MomentsArray &s) {
            return field<double>(s, [](const mcstat_moments &m) { return mcstat_moments_mean(&m); });
        }, "Mean per pixel (NaN where empty).")
        .def_property_readonly("var", [](const MomentsArray &s) {
            return field<double>(s, [](const mcstat_moments &m) { return mcstat_moments_var(&m); });
        }, "Sample variance per pixel, n - 1 (NaN where n < 2).")
        .def_property_readonly("sd", [](const MomentsArray &s) {
            return field<double>(s, [](const mcstat_moments &m) { return mcstat_moments_sd(&m); });
        }, "Sample standard deviation per pixel (NaN where n < 2).")
        .def_property_readonly("min", [](const MomentsArray &s) {
            return field<double>(s, [](const mcstat_moments &m) { return m.n ? m.min : NAN; });
        }, "Smallest value per pixel (NaN where empty).")
        .def_property_readonly("max", [](const MomentsArray &s) {
            return field<double>(s, [](const mcstat_moments &m) { return m.n ? m.max : NAN; });
        }, "Largest value per pixel (NaN where empty).")
        .def("__getitem__", [](const MomentsArray &s, py::handle index) {
            return Moments{s.m[flat_index(s, index)]};
        }, "One pixel's accumulator, as a `Moments` (a copy).")
        .def("__len__", [](const MomentsArray &s) {
            if (s.shape.empty())
                throw py::type_error("len() of a 0-d MomentsArray");
            return static_cast<size_t>(s.shape[0]);
        })
        .def("copy", [](const MomentsArray &s) { return s; }, "An independent copy.")
        .def("__copy__", [](const MomentsArray &s) { return s; })
        .def("__deepcopy__", [](const MomentsArray &s, py::handle) { return s; })
        .def("to_bytes", &to_bytes, R"doc(The accumulators as size * 96 bytes, in C order.

Each pixel's record is `Moments.to_bytes` (versioned, little-endian, with a
checksum), concatenated without a header: the same on every machine and
binding (C: ``mcstat_moments_from_bytes_rows``).  The shape is not stored;
give it to `from_bytes`.)doc")
        .def_static("from_bytes", &from_bytes, py::arg("data"), py::arg("shape") = py::none(),
                    R"doc(An array from `to_bytes` output, of `shape` (default: 1-D, len(data) // 96).

Raises `CorruptDataError` when the length does not match the shape or any
record is corrupt, truncated or of another version.)doc")
        .def("__reduce__", [](py::object self) {
            const MomentsArray &s = self.cast<const MomentsArray &>();
            return py::make_tuple(py::module_::import("mcstat._core").attr("_moments_array_from_bytes"),
                                  py::make_tuple(to_bytes(s), self.attr("shape")));
        })
        .def("__eq__", [](const MomentsArray &a, py::handle b) -> py::object {
            const MomentsArray *mb = as_moments_array(b);
            if (!mb)
                return py::reinterpret_borrow<py::object>(Py_NotImplemented);
            return py::bool_(a.shape == mb->shape &&
                             static_cast<std::string>(to_bytes(a)) == static_cast<std::string>(to_bytes(*mb)));
        })
        .def("__repr__", [](const MomentsArray &s) {
            uint64_t lo = 0, hi = 0;
            for (size_t i = 0; i < s.m.size(); i++) {
                uint64_t n = s.m[i].n;
                if (i == 0 || n < lo)
                    lo = n;
                if (i == 0 || n > hi)
                    hi = n;
            }
            std::string ns = lo == hi ? std::to_string(lo) : std::to_string(lo) + ".." + std::to_string(hi);
            return "MomentsArray(shape=" + shape_str(s.shape) + ", n=" + ns + ")";
        });
    py::setattr(mod.attr("MomentsArray"), "__hash__", py::none());
    mod.def("_moments_array_from_bytes", &from_bytes, py::arg("data"), py::arg("shape") = py::none(),
            "MomentsArray.from_bytes (for pickle).");
}

} // namespace mcs
