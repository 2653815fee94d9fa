# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""``mcstat reproduce``: the case studies of Subr & Arvo's section 3 on a scene.

One concern per module:

=============  ==============================================================
studies        the table of studies (key, section, title, module, report part,
               schema part): a new study is one entry there, its module, its
               report part, its schema entry and its rule in plan
scene          scene files (JSON/TOML), the built-in paper scene, checks
validate       the JSON Schema subset that checks scene files (schema.json)
plan           which studies and tests a scene calls for, and why not others
context        seed streams from --seed, threads, progress bars, stdout
irradiance     3.1: U, C, A, S against Lambert and each other (figures 4, 5)
sampling       3.2: BRDF samplers against rejection sampling (K-S, figure 6)
radiance       3.3: reflected radiance, Welch per direction, binomial test
bugs           3.4: the three planted bugs against the trusted estimator
sequential     3.4+: anytime-valid sequential tests on those bugs, fixed n, H0
timing         error against run time; K-S p-value error against run time
binomial       battery meta-test (libmcstat's exact binomial test), intervals
diagnose       estimator diagnostics: shape, tails, batch size
results        results.json
plots, report  the PNG figures and report.md
run            the driver behind ``mcstat reproduce``
=============  ==============================================================

The numerics are libmcstat's and libmcest's (``mcstat.t_test``,
``var_test``, ``ks_test``, ``batch_means``, ``mcstat.estimators``); these
modules draw samples, count decisions and write them down.
"""
from .plan import Plan
from .scene import PAPER_SCENE, Scene, SceneError, load_scene, parse_scene

__all__ = ["Plan", "Scene", "SceneError", "PAPER_SCENE", "load_scene", "parse_scene", "reproduce"]


def reproduce(*args, **kwargs):
    """See :func:`mcstat_app.reproduce.run.reproduce`."""
    from .run import reproduce as _run

    return _run(*args, **kwargs)
