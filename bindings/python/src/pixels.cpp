// pixels.cpp - Welch's test per pixel on seeds-major image stacks
// (libmcstat's mcstat_pixels_test): float32 or float64 (seeds, ...) arrays
// read in place, optionally a weighted sum of the last axis (the channels:
// luminance from RGB without a float64 copy), the pixels split over
// mcstat.set_num_threads' threads (at most 64) with the GIL released.  For
// mcstat.image.compare.
//
// Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
#include "common.hpp"
#include "output_array.hpp"

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

namespace mcs {

namespace {

bool is_f32(const py::array &a) { return a.dtype().is(py::dtype::of<float>()); }
bool is_f64(const py::array &a) { return a.dtype().is(py::dtype::of<double>()); }

} // namespace

void register_pixels(py::module_ &mod)
{
    mod.def(
        "_t_test_2_pixels",
        [](py::array x, py::array y, py::object weights, int alternative, double alpha, double mu0, bool intervals,
           bool omit_nan, bool render, double resolution, bool paired) {
            if (!(is_f32(x) || is_f64(x)) || !x.dtype().is(y.dtype()))
                throw_invalid("x and y must both be float32 or both float64 arrays, got " +
                              std::string(py::str(x.dtype())) + " and " + std::string(py::str(y.dtype())));
            if (!(x.flags() & py::array::c_style) || !(y.flags() & py::array::c_style))
                throw_invalid("x and y must be C-contiguous (seeds first)");
            bool weighted = !weights.is_none();
            py::ssize_t nd = x.ndim();
            if (nd < 2 || y.ndim() != nd || (weighted && nd < 3))
                throw_invalid("x and y must be (seeds, pixels...)" + std::string(weighted ? " with channels last" : ""));
            for (py::ssize_t k = 1; k < nd; k++)
                if (x.shape(k) != y.shape(k))
                    throw_invalid("x and y must have the same shape after the seeds axis");
            std::vector<double> w;
            size_t channels = 1;
            if (weighted) {
                py::array_t<double, py::array::c_style | py::array::forcecast> wa(weights);
                if (wa.ndim() != 1)
                    throw_invalid("weights must be a 1-D sequence of numbers");
                w.assign(wa.data(), wa.data() + wa.size());
                channels = static_cast<size_t>(x.shape(nd - 1));
                if (w.size() != channels)
                    throw_invalid("weights must have one entry per channel (" + std::to_string(channels) + "), got " +
                                  std::to_string(w.size()));
            }
            std::vector<py::ssize_t> shape;
            size_t pixels = 1;
            for (py::ssize_t k = 1; k < nd - (weighted ? 1 : 0); k++) {
                shape.push_back(x.shape(k));
                pixels *= static_cast<size_t>(x.shape(k));
            }
            size_t nx = static_cast<size_t>(x.shape(0)), ny = static_cast<size_t>(y.shape(0));
            if (paired && nx != ny)
                throw_invalid("paired tests need the same number of seeds on both sides (the pairs), got " +
                              std::to_string(nx) + " and " + std::to_string(ny));
            const int test = paired ? MCSTAT_TEST_T_PAIRED : MCSTAT_TEST_T_2;
            size_t stride = pixels * channels;
            const double *wp = weighted ? w.data() : nullptr;
            unsigned flags = (intervals ? 0u : MCSTAT_ROWS_NO_INTERVALS) | (omit_nan ? MCSTAT_ROWS_OMIT_NAN : 0u) |
                             (render ? MCSTAT_PIXELS_RENDER : 0u);
            bool f32 = is_f32(x);
            auto p = output_array<double>(shape), t = output_array<double>(shape), df = output_array<double>(shape),
                 mx = output_array<double>(shape), my = output_array<double>(shape), se = output_array<double>(shape);
            std::vector<py::ssize_t> none{0};
            auto lo = output_array<double>(intervals ? shape : none), hi = output_array<double>(intervals ? shape : none);
            auto status = output_array<int32_t>(shape);
            mcstat_pixels_out out = MCSTAT_PIXELS_OUT_INIT;
            out.p_value = p.mutable_data();
            out.statistic = t.mutable_data();
            out.df = df.mutable_data();
            out.estimate = mx.mutable_data();
            out.estimate2 = my.mutable_data();
            out.std_error = se.mutable_data();
            out.conf_lo = intervals ? lo.mutable_data() : nullptr;
            out.conf_hi = intervals ? hi.mutable_data() : nullptr;
            out.status = status.mutable_data();
            mcstat_pixels_in px = MCSTAT_PIXELS_IN_INIT, py_ = MCSTAT_PIXELS_IN_INIT;
            px.type = py_.type = f32 ? MCSTAT_VALUE_FLOAT32 : MCSTAT_VALUE_FLOAT64;
            px.data = x.data();
            py_.data = y.data();
            px.n = nx;
            py_.n = ny;
            px.value_stride = py_.value_stride = stride;
            px.pixel_stride = py_.pixel_stride = px.channels = py_.channels = channels;
            px.weights = py_.weights = wp;
            mcstat_pixels_options opt = MCSTAT_PIXELS_OPTIONS_INIT;
            opt.flags = flags;
            opt.threads = std::min(num_threads(), 64);
            opt.resolution = resolution;
            // the arguments first, on an empty range: their errors raise, a
            // pixel's only sets its status
            int st = mcstat_pixels_test(test, &px, &py_, 0, 0, mu0, alternative, alpha, &opt, &out);
            if (st)
                throw_status(st, "mcstat_pixels_test");
            {
                py::gil_scoped_release nogil;
                mcstat_pixels_test(test, &px, &py_, 0, pixels, mu0, alternative, alpha, &opt, &out);
            }
            py::dict d;
            d["pvalue"] = p;
            d["statistic"] = t;
            d["df"] = df;
            d["mean_x"] = mx;
            d["mean_y"] = my;
            d["std_error"] = se;
            d["status"] = status;
            if (intervals) {
                d["conf_lo"] = lo;
                d["conf_hi"] = hi;
            }
            return d;
        },
        py::arg("x"), py::arg("y"), py::arg("weights") = py::none(), py::arg("alternative") = 0,
        py::arg("alpha") = 0.05, py::arg("mu0") = 0.0, py::arg("intervals") = false, py::arg("omit_nan") = false,
        py::arg("render") = false, py::arg("resolution") = 0.0, py::arg("paired") = false,
        "Welch's test (paired: the paired t test, mean_x its mean difference, mean_y NaN) per pixel of x against y, (seeds, ...) float32 or float64 C-contiguous arrays read in "
        "place; with weights, the tested value is the weighted sum over the last axis. Returns a dict of arrays "
        "of the pixel shape: pvalue, statistic, df, mean_x, mean_y, std_error, status (and conf_lo, conf_hi with "
        "intervals). render: libmcstat's MCSTAT_PIXELS_RENDER guards (resolution: their numerical floor, 0 = from "
        "the dtype).");
    mod.attr("RESOLUTION_FLOAT32") = MCSTAT_RESOLUTION_FLOAT32;
    mod.attr("RESOLUTION_FLOAT64") = MCSTAT_RESOLUTION_FLOAT64;
}

} // namespace mcs
