// sequential.cpp - mcstat.SequentialTest: libmcstat's mcstat_seq
// (mcstat/sequential.h), an anytime-valid test looked at after every push.
//
// The state is the C struct itself (plain data, 448 bytes): every number,
// decision and sentence comes from libmcstat; this file names arguments in
// errors and turns hold bits into words.
//
// Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
#include "common.hpp"

#include <climits>
#include <cmath>
#include <cstdio>
#include <string>

namespace mcs {

namespace {

struct Sequential {
    mcstat_seq s;
};

int parse_kind(py::handle kind)
{
    if (!py::isinstance<py::str>(kind))
        throw py::type_error("kind must be a str (\"mean\", \"mean2\", \"var\" or \"var2\"), got " + repr(kind.ptr()));
    std::string k = kind.cast<std::string>();
    for (int i = MCSTAT_SEQ_MEAN_1; i <= MCSTAT_SEQ_VAR_2; i++)
        if (k == mcstat_seq_kind_name(i))
            return i;
    throw_invalid("kind must be \"mean\", \"mean2\", \"var\" or \"var2\", got " + repr(kind.ptr()));
}

double finite_arg(py::handle v, const char *name)
{
    double d = get_double(v.ptr(), name);
    if (!std::isfinite(d))
        throw_invalid(std::string(name) + " must be finite, got " + repr(v.ptr()));
    return d;
}

// The null value from the argument the kind takes; the others must be None.
double null_value(int kind, py::handle mu, py::handle sigma2, py::handle ratio)
{
    const char *names[] = {"mu", "sigma2", "ratio"};
    py::handle given[] = {mu, sigma2, ratio};
    int want = kind == MCSTAT_SEQ_VAR_1 ? 1 : kind == MCSTAT_SEQ_VAR_2 ? 2 : 0;
    for (int i = 0; i < 3; i++)
        if (i != want && !given[i].is_none())
            throw_invalid(std::string(names[i]) + " does not apply to kind \"" + mcstat_seq_kind_name(kind) +
                          "\" (it takes " + names[want] + ")");
    py::handle v = given[want];
    if (v.is_none()) {
        if (want == 1)
            throw_invalid("kind \"var\" needs sigma2, the variance under H0");
        return want == 2 ? 1.0 : 0.0;
    }
    double d = finite_arg(v, names[want]);
    if (want > 0 && !(d > 0.0))
        throw_invalid(std::string(names[want]) + " must be > 0, got " + repr(v.ptr()));
    return d;
}

bool two_sample(const Sequential &q) { return q.s.kind == MCSTAT_SEQ_MEAN_2 || q.s.kind == MCSTAT_SEQ_VAR_2; }

bool batch_has_nonfinite(const py::array &a)
{
    const double *v = static_cast<const double *>(a.data());
    for (py::ssize_t i = 0; i < a.size(); i++)
        if (!std::isfinite(v[i]))
            return true;
    return false;
}

// A batch as an accumulator: a Moments as it is, anything else as float64 values.
mcstat_moments batch_of(py::handle obj, const char *name)
{
    if (const mcstat_moments *m = as_moments(obj))
        return *m;
    py::array a = as_contiguous_array(obj, name);
    mcstat_moments m;
    mcstat_moments_init(&m);
    size_t n = static_cast<size_t>(a.size());
    int st = n ? mcstat_moments_add_array(&m, static_cast<const double *>(a.data()), n) : MCSTAT_OK;
    if (st)
        throw_status(st, st == MCSTAT_ENONFINITE ? std::string(name) + " contains NaN or infinite values"
                                                 : std::string("pushing ") + name);
    return m;
}

// Arrays go to libmcstat as they are (mcstat_seq_push_array[_2]); a Moments
// or a Stream (a renderer's frame) as its accumulator.
void push(Sequential &q, py::handle x, py::handle y)
{
    int st;
    std::string what = "push";
    if (two_sample(q)) {
        if (y.is_none())
            throw_invalid(std::string("kind \"") + mcstat_seq_kind_name(q.s.kind) + "\" pushes two batches: push(x, y)");
        if (as_moments(x) || as_moments(y)) {
            mcstat_moments bx = batch_of(x, "x"), by = batch_of(y, "y");
            st = mcstat_seq_push_2_moments(&q.s, &bx, &by);
        } else {
            py::array ax = as_contiguous_array(x, "x"), ay = as_contiguous_array(y, "y");
            st = mcstat_seq_push_2_array(&q.s, static_cast<const double *>(ax.data()), static_cast<size_t>(ax.size()),
                                         static_cast<const double *>(ay.data()), static_cast<size_t>(ay.size()));
            if (st == MCSTAT_ENONFINITE)
                what = batch_has_nonfinite(ax) ? "x contains NaN or infinite values" : "y contains NaN or infinite values";
        }
    } else {
        if (!y.is_none())
            throw_invalid(std::string("kind \"") + mcstat_seq_kind_name(q.s.kind) + "\" takes one batch: push(x)");
        if (const mcstat_stream *frame = as_stream(x)) {
            st = mcstat_seq_push_stream(&q.s, frame);
            if (st == MCSTAT_ENONFINITE)
                what = "the stream x has seen NaN or infinite values";
        } else if (as_moments(x)) {
            mcstat_moments bx = batch_of(x, "x");
            st = mcstat_seq_push_moments(&q.s, &bx);
        } else {
            py::array ax = as_contiguous_array(x, "x");
            st = mcstat_seq_push_array(&q.s, static_cast<const double *>(ax.data()), static_cast<size_t>(ax.size()));
            if (st == MCSTAT_ENONFINITE)
                what = "x contains NaN or infinite values";
        }
    }
    if (st)
        throw_status(st, st == MCSTAT_ETOOBIG ? "the count would pass 2**64 - 1" : what);
}

mcstat_result result_of(const Sequential &q)
{
    mcstat_result r;
    int st = mcstat_seq_result(&q.s, &r);
    if (st)
        throw_status(st, "sequential test state");
    return r;
}

py::object hold_text(const Sequential &q)
{
    if (q.s.state == MCSTAT_SEQ_DECIDED || !q.s.hold)
        return py::none();
    if (q.s.hold & MCSTAT_SEQ_HOLD_DEGENERATE)
        return py::str("no spread yet");
    if (q.s.hold & MCSTAT_SEQ_HOLD_KURTOSIS) {
        mcstat_result r = result_of(q);
        char buf[128];
        std::snprintf(buf, sizeof buf, "heavy tails: the kurtosis asks for n >= %.0f", std::ceil(r.seq_n_gate));
        return py::str(buf);
    }
    return py::str("too few values (min_n " + std::to_string(q.s.min_n) + ")");
}

const char *decision_text(const Sequential &q)
{
    return q.s.state == MCSTAT_SEQ_DECIDED ? mcstat_decision_name(q.s.decision) : "continue";
}

std::string block(const Sequential &q)
{
    mcstat_result r = result_of(q);
    size_t len = 0;
    mcstat_result_format(&r, "x", "y", nullptr, 0, &len);
    std::string out(len + 1, '\0');
    mcstat_result_format(&r, "x", "y", &out[0], out.size(), &len);
    out.resize(len);
    return out;
}

} // namespace

void register_sequential(py::module_ &mod)
{
    py::class_<Sequential>(mod, "SequentialTest", R"doc(
An anytime-valid sequential test: push a batch, look, stop as soon as it
decides, in either direction, with the error rate still at most alpha
(libmcstat's ``mcstat_seq``; mcstat/sequential.h).

>>> s = mcstat.SequentialTest("mean", mu=E, alpha=0.01)
>>> while not s.decided and s.n < 1_000_000:
...     s.push(render(1000))
>>> s.decision, s.pvalue, s.conf_seq

Kinds: ``"mean"`` (mean of x against `mu`, default 0), ``"mean2"`` (mean of
x minus mean of y against `mu`, default 0; ``push(x, y)``), ``"var"``
(variance against `sigma2`, required), ``"var2"`` (var(x)/var(y) against
`ratio`, default 1; ``push(x, y)``).  `decision` is ``"continue"`` until the
test decides, then ``"less"``, ``"greater"`` or, with an equivalence margin
``eps > 0`` (means, two-sided), ``"equal"``: the mean is within eps of `mu`.

The method is the asymptotic Gaussian-mixture confidence sequence: it
assumes independent, identically distributed values with finite variance
(fourth moment for the variances), and holds (no decision, `hold` says
why) while a sample has fewer than `min_n` values, no spread, or fewer than
``kurtosis_gate`` times its kurtosis in values, the regime where heavy
tails and exact zeros fool it.  `t_opt` is the n where the sequence is
tightest.  A batch is an array or a `Moments` (per-thread accumulators
merged); each push is one look.

Parameters
----------
kind : str
mu, sigma2, ratio : float, optional
    The null value; only the one `kind` takes may be given.
alpha : float
alternative : {"two-sided", "less", "greater"}
eps : float
    Equivalence margin >= 0 on the mean (0: never decides "equal").
t_opt : float
kurtosis_gate : float
var_ucb_z : float
    The variance is replaced by its upper confidence bound s^2 + var_ucb_z
    times its standard error (0: plain s^2).
min_n : int
)doc")
        .def(py::init([](py::handle kind, py::handle mu, py::handle sigma2, py::handle ratio, py::handle alpha,
                         py::handle alternative, py::handle eps, py::handle t_opt, py::handle kurtosis_gate,
                         py::handle var_ucb_z, py::handle min_n) {
                 Sequential q;
                 int k = parse_kind(kind);
                 double null = null_value(k, mu, sigma2, ratio);
                 mcstat_seq_options o;
                 mcstat_seq_options_init(&o);
                 o.alternative = parse_alternative(alternative.ptr());
                 o.alpha = get_double(alpha.ptr(), "alpha");
                 if (!(o.alpha > 0.0 && o.alpha < 1.0))
                     throw_invalid("alpha must be in (0, 1), got " + repr(alpha.ptr()));
                 o.eps = finite_arg(eps, "eps");
                 if (o.eps < 0.0)
                     throw_invalid("eps must be >= 0, got " + repr(eps.ptr()));
                 if (o.eps > 0.0 && (k == MCSTAT_SEQ_VAR_1 || k == MCSTAT_SEQ_VAR_2))
                     throw_invalid("eps (an equivalence margin on the mean) does not apply to kind \"" +
                                   std::string(mcstat_seq_kind_name(k)) + "\"");
                 if (o.eps > 0.0 && o.alternative != MCSTAT_TWO_SIDED)
                     throw_invalid("eps needs alternative=\"two-sided\" (equivalence is two-sided)");
                 o.t_opt = finite_arg(t_opt, "t_opt");
                 if (!(o.t_opt > 0.0))
                     throw_invalid("t_opt must be > 0, got " + repr(t_opt.ptr()));
                 o.kurtosis_gate = finite_arg(kurtosis_gate, "kurtosis_gate");
                 if (o.kurtosis_gate < 0.0)
                     throw_invalid("kurtosis_gate must be >= 0, got " + repr(kurtosis_gate.ptr()));
                 o.var_ucb_z = finite_arg(var_ucb_z, "var_ucb_z");
                 if (o.var_ucb_z < 0.0)
                     throw_invalid("var_ucb_z must be >= 0, got " + repr(var_ucb_z.ptr()));
                 if (PyBool_Check(min_n.ptr()) || !PyIndex_Check(min_n.ptr()))
                     throw py::type_error("min_n must be an int, got " + repr(min_n.ptr()));
                 py::int_ mi = py::reinterpret_steal<py::int_>(PyNumber_Index(min_n.ptr()));
                 int overflow = 0;
                 long long mn = PyLong_AsLongLongAndOverflow(mi.ptr(), &overflow);
                 if (overflow > 0)
                     mn = LLONG_MAX;
                 if (overflow < 0 || mn < 2)
                     throw_invalid("min_n must be >= 2, got " + repr(min_n.ptr()));
                 o.min_n = static_cast<uint64_t>(mn);
                 int st = mcstat_seq_init(&q.s, k, null, &o);
                 if (st)
                     throw_status(st, "SequentialTest arguments");
                 return q;
             }),
             py::arg("kind") = "mean", py::kw_only(), py::arg("mu") = py::none(), py::arg("sigma2") = py::none(),
             py::arg("ratio") = py::none(), py::arg("alpha") = 0.05, py::arg("alternative") = "two-sided",
             py::arg("eps") = 0.0, py::arg("t_opt") = 1e4, py::arg("kurtosis_gate") = 10.0,
             py::arg("var_ucb_z") = 3.0, py::arg("min_n") = 100)
        .def(
            "push",
            [](Sequential &q, py::handle x, py::handle y) -> Sequential & {
                push(q, x, y);
                return q;
            },
            py::arg("x"), py::arg("y") = py::none(), py::return_value_policy::reference_internal,
            R"doc(Adds a batch (an array of values, a `Moments` or a `Stream`) and looks; returns self.

Two-sample kinds take ``push(x, y)`` (either batch may be empty).  Raises
`NonFiniteError` (the batch is then not added) for NaN or infinities.)doc")
        .def_property_readonly("kind", [](const Sequential &q) { return py::str(mcstat_seq_kind_name(q.s.kind)); })
        .def_property_readonly("n", [](const Sequential &q) { return q.s.x.n; }, "Values of x pushed so far.")
        .def_property_readonly("n_y", [](const Sequential &q) { return q.s.y.n; }, "Values of y (two-sample kinds).")
        .def_property_readonly("looks", [](const Sequential &q) { return q.s.looks; })
        .def_property_readonly("decided", [](const Sequential &q) { return q.s.state == MCSTAT_SEQ_DECIDED; })
        .def_property_readonly("reject", [](const Sequential &q) {
            return q.s.state == MCSTAT_SEQ_DECIDED && q.s.decision != MCSTAT_DECISION_EQUAL;
        }, "True once decided \"less\" or \"greater\" (H0 rejected).")
        .def_property_readonly("decision", [](const Sequential &q) { return py::str(decision_text(q)); },
                               "\"continue\", or the decision: \"less\", \"equal\" or \"greater\".")
        .def_property_readonly("n_decided", [](const Sequential &q) -> py::object {
            return q.s.state == MCSTAT_SEQ_DECIDED ? py::object(py::int_(q.s.n_decided)) : py::object(py::none());
        }, "n (of x) at the look that decided; None while continuing.")
        .def_property_readonly("pvalue", [](const Sequential &q) { return result_of(q).p_value; },
                               "The anytime-valid p-value: valid at whatever time the pushing stops.")
        .def_property_readonly("log_pvalue", [](const Sequential &q) {
            mcstat_result r = result_of(q);
            double lp;
            return mcstat_result_log_p_value(&r, &lp) == MCSTAT_OK ? lp : NAN;
        })
        .def_property_readonly("conf_seq", [](const Sequential &q) {
            mcstat_result r = result_of(q);
            return py::make_tuple(r.conf_int[0], r.conf_int[1]);
        }, "The confidence sequence (lo, hi) at level 1 - alpha: it covers the parameter at every look at once.")
        .def_property_readonly("statistic", [](const Sequential &q) { return result_of(q).statistic; },
                               "z of the last look (NaN while held).")
        .def_property_readonly("estimate", [](const Sequential &q) -> py::object {
            mcstat_result r = result_of(q);
            if (q.s.kind == MCSTAT_SEQ_MEAN_2)
                return py::make_tuple(r.estimate[0], r.estimate[1]);
            return py::float_(r.estimate[0]);
        })
        .def_property_readonly("hold", &hold_text,
                               "Why no decision is allowed yet (None when the data allow one or it is decided).")
        .def_property_readonly("alpha", [](const Sequential &q) { return q.s.alpha; })
        .def_property_readonly("alternative",
                               [](const Sequential &q) { return py::str(mcstat_alternative_name(q.s.alternative)); })
        .def_property_readonly("null_value", [](const Sequential &q) { return q.s.null_value; })
        .def("result", [](const Sequential &q) { return make_result(result_of(q)); },
             "The state as a `TestResult` (its `method` names the sequential test; `conf_int` is the sequence).")
        .def(
            "finish",
            [](const Sequential &q) {
                mcstat_result r;
                int st = mcstat_seq_finish(&q.s, &r);
                if (st == MCSTAT_EHEAVYTAIL) {
                    char buf[256];
                    std::snprintf(buf, sizeof buf,
                                  "undecided after n = %llu: the kurtosis asks for n >= %.0f before a decision "
                                  "(infinite variance, or far more samples needed)",
                                  static_cast<unsigned long long>(q.s.x.n), std::ceil(r.seq_n_gate));
                    throw_status(st, buf);
                }
                if (st)
                    throw_status(st, "sequential test state");
                return make_result(r);
            },
            R"doc(The test at the end of the budget, as a `TestResult`.

Raises `HeavyTailError` when the kurtosis gate never opened: the tails were
too heavy for a decision within the samples pushed.  Undecided otherwise
is not an error: ``decision`` stays "continue" (not enough evidence yet).)doc")
        .def("__copy__", [](const Sequential &q) { return q; })
        .def("__deepcopy__", [](const Sequential &q, py::handle) { return q; }, py::arg("memo"))
        .def("__str__", &block)
        .def("__repr__", [](const Sequential &q) {
            char buf[320];
            std::snprintf(buf, sizeof buf, "<SequentialTest %s: n=%llu, looks=%llu, decision=%s, pvalue=%.4g>",
                          mcstat_seq_kind_name(q.s.kind), static_cast<unsigned long long>(q.s.x.n),
                          static_cast<unsigned long long>(q.s.looks), decision_text(q), result_of(q).p_value);
            return std::string(buf);
        });
}

} // namespace mcs
