"""Every refusal of the renderer checks says why, in C's words: the
binding converts its arguments and passes C's reason on
(mcstat_last_error(), the field's C prefix "options." or "model."
dropped), so each argument's range is written once, in libmcstat.  Each
case here is the whole message, so a reason that drifts from the
argument's name or value fails; and the binding's source holds none of
the ranges."""
import os
import re

import numpy as np
import pytest

import mcstat
from conftest import ROOT

WI = np.array([0.0, 0.0, 1.0])


def _sample(wi, u):
    r, phi = np.sqrt(u[:, 0]), 2 * np.pi * u[:, 1]
    wo = np.stack([r * np.cos(phi), r * np.sin(phi), np.sqrt(np.maximum(0, 1 - u[:, 0]))], axis=1)
    return wo, np.ones(len(u)), wo[:, 2] / np.pi


def _pdf(wi, wo):
    return np.maximum(np.asarray(wo)[:, 2], 0) / np.pi


CASES = [
    (dict(n=10), "n must be at least 1000, got 10"),
    (dict(alpha=1.5), "alpha must be in (0, 1), got 1.5"),
    (dict(cells=1), "cells must be 0 (automatic) or 2..1048576, got 1"),
    (dict(batch=3), "batch must be in 64..2^32, got 3"),
    (dict(rtol=0.0), "rtol must be in (0, 1), got 0"),
    (dict(tolerated=1.0), "tolerated must be in [0, 1), got 1"),
    (dict(resolution=0.5), "resolution must be 0 (derived from the values) or in (0, 0.01), got 0.5"),
    (dict(n_uniforms=9), "n_uniforms must be in 1..8, got 9"),
    (dict(n_pilot=10), "n_pilot must be 0 (automatic) or at least 64, got 10"),
    (dict(n_eval=10), "n_eval must be 0 (n) or at least 1000, got 10"),
    (dict(domain="disk"), "domain of a BSDF must be sphere or hemisphere (directions), got disk"),
]


@pytest.mark.parametrize("kw,message", CASES, ids=[next(iter(k)) for k, _ in CASES])
def test_bsdf_refusal_is_cs_reason(kw, message):
    with pytest.raises(mcstat.InvalidArgumentError) as e:
        mcstat.check_bsdf(_sample, _pdf, _pdf, WI, **kw)
    assert str(e.value) == message


def test_wi_refusal():
    with pytest.raises(mcstat.InvalidArgumentError) as e:
        mcstat.check_bsdf(_sample, _pdf, _pdf, [0.0, 0.0, 0.0])
    assert str(e.value) == "wi must be a finite, non-zero direction, got (0, 0, 0)"


def test_phase_domain_and_medium_sigma_ref():
    with pytest.raises(mcstat.InvalidArgumentError) as e:
        mcstat.check_warp(lambda u: u, lambda x: np.ones(len(x)), domain="square", n=10)
    assert str(e.value) == "n must be at least 1000, got 10"
    with pytest.raises(mcstat.InvalidArgumentError) as e:
        mcstat.check_medium(lambda wi, u: (u[:, :1], np.ones(len(u)), np.ones(len(u))),
                            lambda wi, x: np.ones(len(x)), lambda wi, x: np.ones(len(x)), sigma_ref=-1.0)
    assert str(e.value) == "sigma_ref must be finite and > 0, got -1"


def test_a_later_success_leaves_no_reason():
    with pytest.raises(mcstat.InvalidArgumentError):
        mcstat.check_bsdf(_sample, _pdf, _pdf, WI, n=10)
    r = mcstat.check_bsdf(_sample, _pdf, _pdf, WI, n=2000, seed=1)
    assert r.verdict in ("consistent", "inconsistent", "inconclusive")


def test_the_binding_holds_no_range():
    """The ranges C checks appear nowhere in the binding's source."""
    src = open(os.path.join(ROOT, "bindings", "python", "src", "check.cpp")).read()
    for literal in ("1048576", "2^32", "(0, 0.01)", "at least 1000", "must be in (0, 1)", "tolerated must",
                    "rtol must", "batch must", "cells must", "must be a finite number > 0", "finite and non-zero"):
        assert literal not in src, literal
    assert not re.search(r"n_uniforms must be in", src)
