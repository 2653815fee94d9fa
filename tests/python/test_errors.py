"""Every bad input raises the documented exception."""
import numpy as np
import pytest

import mcstat

GOOD = np.array([1.0, 2.0, 4.0, 3.5, 0.5])


@pytest.mark.parametrize("func", [mcstat.t_test, lambda x, **kw: mcstat.var_test(x, sigma2=1.0, **kw)])
class TestOneSample:
    def test_nan_and_inf(self, func):
        with pytest.raises(mcstat.NonFiniteError, match="NaN or infinite"):
            func(np.array([1.0, np.nan, 3.0]))
        with pytest.raises(mcstat.NonFiniteError):
            func(np.array([1.0, np.inf, 3.0]))
        with pytest.raises(mcstat.NonFiniteError):
            func(np.array([1.0, -np.inf, 3.0]), nan_policy="omit")

    def test_too_few(self, func):
        with pytest.raises(mcstat.TooFewObservationsError, match=r"too few observations.*\(x has 0 values\)"):
            func(np.array([]))
        with pytest.raises(mcstat.TooFewObservationsError, match="x has 1 values"):
            func([1.0])
        with pytest.raises(mcstat.TooFewObservationsError):
            func([1.0, np.nan, np.nan], nan_policy="omit")

    def test_zero_variance(self, func):
        with pytest.raises(mcstat.DegenerateDataError, match="zero spread"):
            func(np.full(10, 3.0))
        with pytest.raises(mcstat.DegenerateDataError):
            func(1e9 + np.array([0.0, 1e-8, 0.0, 1e-8]))  # below 10 eps |mean|

    @pytest.mark.parametrize("alpha", [0.0, 1.0, -0.1, 1.5, np.nan, np.inf])
    def test_alpha(self, func, alpha):
        with pytest.raises(mcstat.InvalidArgumentError, match=r"alpha must be in \(0, 1\)"):
            func(GOOD, alpha=alpha)

    def test_strings(self, func):
        with pytest.raises(mcstat.InvalidArgumentError, match="alternative must be"):
            func(GOOD, alternative="two.tailed")
        with pytest.raises(mcstat.InvalidArgumentError, match="nan_policy must be"):
            func(GOOD, nan_policy="ignore")  # ("propagate" is SciPy's, accepted)
        with pytest.raises(mcstat.InvalidArgumentError, match="on_error must be"):
            func(GOOD, on_error="ignore")
        with pytest.raises(TypeError, match="alternative must be a str"):
            func(GOOD, alternative=1)
        with pytest.raises(TypeError, match="unexpected keyword argument 'alternatve'"):
            func(GOOD, alternatve="less")

    def test_dims_and_types(self, func):
        with pytest.raises(mcstat.InvalidArgumentError, match="at least 1-D"):
            func(3.0)
        with pytest.raises(mcstat.InvalidArgumentError, match="axis 1 is out of range"):
            func(GOOD, axis=1)
        with pytest.raises(TypeError, match="not None"):
            func(None)
        with pytest.raises((TypeError, ValueError)):
            func(["a", "b"])
        with pytest.raises(TypeError, match="alpha must be a real number"):
            func(GOOD, alpha="0.05")


def test_two_sample_errors():
    with pytest.raises(mcstat.TooFewObservationsError, match="y has 1"):
        mcstat.t_test(GOOD, [1.0])
    with pytest.raises(mcstat.NonFiniteError):
        mcstat.t_test(GOOD, [1.0, np.nan])
    with pytest.raises(mcstat.DegenerateDataError):
        mcstat.t_test(np.ones(4), np.ones(6) * 2)
    assert mcstat.t_test(np.ones(4), GOOD).pvalue > 0  # Welch: one constant sample is fine (R's rule)
    with pytest.raises(mcstat.DegenerateDataError):
        mcstat.var_test(GOOD, np.ones(4))
    with pytest.raises(mcstat.InvalidArgumentError, match="mu must be finite"):
        mcstat.t_test(GOOD, GOOD, mu=np.inf)
    with pytest.raises(mcstat.InvalidArgumentError, match="same number of dimensions"):
        mcstat.t_test(GOOD, np.ones((2, 5)))
    with pytest.raises(mcstat.InvalidArgumentError, match="must be 1-D"):
        mcstat.t_test(mcstat.Moments(GOOD), np.ones((2, 5)))
    with pytest.raises(TypeError, match="at most 2 positional"):
        mcstat.t_test(GOOD, GOOD, GOOD)
    with pytest.raises(TypeError, match="multiple values"):
        mcstat.t_test(GOOD, x=GOOD)
    with pytest.raises(TypeError, match="missing required argument 'x'"):
        mcstat.t_test()


def test_exception_hierarchy_and_text():
    for cls, status in [(mcstat.InvalidArgumentError, 1), (mcstat.TooFewObservationsError, 2),
                        (mcstat.NonFiniteError, 3), (mcstat.DegenerateDataError, 4),
                        (mcstat.OutOfMemoryError, 5), (mcstat.NumericalError, 6), (mcstat.BufferSizeError, 7),
                        (mcstat.CorruptDataError, 8)]:
        assert issubclass(cls, mcstat.McstatError) and issubclass(cls, ValueError)
        assert cls.status == status
    assert issubclass(mcstat.OutOfMemoryError, MemoryError)
    try:
        mcstat.t_test([1.0, np.nan])
    except mcstat.NonFiniteError as e:
        assert str(e) == "the data contain NaN or infinite values"  # mcstat_strerror's sentence
        assert e.status == 3 and e.rows is None


# ---- messages in Python's words -------------------------------------------------

C_WORDING = ("NULL pointer", "unknown option", "parameter outside its domain")


@pytest.mark.parametrize("call, want", [
    (lambda: mcstat.t_test([1.0, 2.0, 3.0], alpha=5), r"^alpha must be in \(0, 1\), got 5"),
    (lambda: mcstat.var_test([1.0, 2.0, 3.0], sigma2=-1), r"^sigma2 must be positive"),
    (lambda: mcstat.t_test([1.0, 2.0, 3.0], alternative="foo"), r"^alternative must be"),
    (lambda: mcstat.p_adjust([0.1], method="nope"), r"^method must be one of"),
    (lambda: mcstat.binom_test(3, 2), r"^x \(successes\) must be at most n \(trials\), got x=3, n=2$"),
])
def test_invalid_argument_messages_name_the_argument(call, want):
    with pytest.raises(mcstat.InvalidArgumentError, match=want) as e:
        call()
    assert not any(w in str(e.value) for w in C_WORDING), str(e.value)


def test_binom_test_zero_trials_speaks_of_trials():
    with pytest.raises(mcstat.TooFewObservationsError) as e:
        mcstat.binom_test(0, 0)
    msg = str(e.value)
    assert "n >= 1 trials" in msg and "K-S" not in msg and "chi-squared" not in msg, msg


def test_row_errors_do_not_speak_of_other_tests():
    x = np.ones((3, 1))  # one value per row: too few for the t test
    with pytest.raises(mcstat.TooFewObservationsError) as e:
        mcstat.t_test(x, mu=0.0)
    assert "K-S" not in str(e.value) and "3 of 3 rows failed" in str(e.value)


def test_errors_carry_the_c_status_text():
    # the message is in Python's words; the C sentence stays on the exception
    with pytest.raises(mcstat.InvalidArgumentError) as e:
        mcstat.t_test([1.0, 2.0, 3.0], alpha=5)
    assert str(e.value) == "alpha must be in (0, 1), got 5"
    assert e.value.status_text == mcstat._core.strerror(1) and e.value.status_text.startswith("invalid argument")
    with pytest.raises(mcstat.DegenerateDataError) as e:
        mcstat.t_test([2.0, 2.0, 2.0])
    assert e.value.status_text == mcstat._core.strerror(e.value.status)
