# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""A Mitsuba phase function as the callables of mcstat.check_phase.

Conventions: mcstat's wi is Mitsuba's mei.wi (pointing back along the
ray, in world space; mei.sh_frame is built around it as
sample_interaction builds it), wo what sample() returns.  Mitsuba's
sample(ctx, mei, sample1, sample2) takes 3 uniforms (sample1 picks a
component of a blend).  eval is the value of eval_pdf, the weight
sample()'s, pdf sample()'s; a sample with pdf <= 0 is a failed one.
"""
from __future__ import annotations

from typing import Any, Optional, Tuple

import numpy as np

from .. import _core
from . import _env


class PhaseModel:
    """A Mitsuba phase function as ``sample(wi, u)``, ``eval(wi, wo)`` and
    ``pdf(wi, wo)``, channel ``channel`` of its value and weight."""

    n_uniforms = 3

    def __init__(self, phase: Any, *, channel: int = 0, variant: Optional[str] = None) -> None:
        self.phase, self.variant = _env.resolve(phase, "PhaseFunction", "phase", variant)
        self.channel = int(channel)
        with _env.in_variant(self.variant) as mi:
            self.ctx = mi.PhaseFunctionContext(None)
        self.eval(np.array([0.0, 0.0, 1.0]), np.array([[0.0, 0.0, 1.0]]))  # the channel exists

    def _mei(self, mi: Any, width: int, wi: np.ndarray) -> Any:
        mei = _env.zeros(self.variant, mi.MediumInteraction3f, width)
        mei.wi = _env.constant(self.variant, mi.Vector3f, wi)
        mei.sh_frame = mi.Frame3f(mei.wi)
        return mei

    def sample(self, wi: Any, u: Any) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
        wi = np.asarray(wi, dtype=np.float64)
        u = _env.uniforms(u, self.variant)
        ch = self.channel
        with _env.in_variant(self.variant) as mi:

            def one(width: int, u0: Any, u12: Any) -> Tuple[Any, ...]:
                mei = self._mei(mi, width, wi)
                wo, w, pdf = self.phase.sample(self.ctx, mei, u0, u12)
                return wo, _env.channel_of(w, ch, "the weight"), pdf, w, mei

            wo, weight, pdf = _env.batch(self.variant, one, len(u), [(mi.Float, u[:, 0]), (mi.Point2f, u[:, 1:3])],
                                         n_out=3)
        ok = pdf > 0
        n = np.linalg.norm(wo, axis=1)
        wo = np.where(n[:, None] > 0, wo / np.where(n > 0, n, 1.0)[:, None], wo)  # float32 directions, renormalised
        return wo, np.where(ok, weight, 0.0), np.where(ok, pdf, 0.0)

    def _eval_pdf(self, wi: Any, wo: Any, which: int) -> np.ndarray:
        wi = np.asarray(wi, dtype=np.float64)
        wo = np.asarray(wo, dtype=np.float64).reshape(-1, 3)
        ch = self.channel
        with _env.in_variant(self.variant) as mi:

            def one(width: int, d: Any) -> Tuple[Any, ...]:
                mei = self._mei(mi, width, wi)
                v, p = self.phase.eval_pdf(self.ctx, mei, d)
                return (_env.channel_of(v, ch, "eval()") if which == 0 else p), v, p, mei

            return _env.batch(self.variant, one, len(wo), [(mi.Vector3f, wo)], n_out=1)[0]

    def eval(self, wi: Any, wo: Any) -> np.ndarray:
        return self._eval_pdf(wi, wo, 0)

    def pdf(self, wi: Any, wo: Any) -> np.ndarray:
        return self._eval_pdf(wi, wo, 1)


def phase_model(phase: Any, *, channel: int = 0, variant: Optional[str] = None) -> PhaseModel:
    """The callables of a Mitsuba phase function (plugin dict or loaded): see `PhaseModel`."""
    return PhaseModel(phase, channel=channel, variant=variant)


def check_phase(phase: Any, wi: Any, *, channel: int = 0, variant: Optional[str] = None,
                **check_kwargs: Any) -> _core.CheckReport:
    """mcstat.check_phase on a Mitsuba phase function: ``check_phase({"type":
    "hg", "g": 0.7}, wi)``.  ``wi`` (normalised here) is Mitsuba's mei.wi;
    ``check_kwargs`` go to `mcstat.check_phase`; ``n_uniforms`` is
    Mitsuba's 3."""
    if "n_uniforms" in check_kwargs and check_kwargs["n_uniforms"] != PhaseModel.n_uniforms:
        raise ValueError(f"n_uniforms: a Mitsuba phase function takes {PhaseModel.n_uniforms} uniforms, "
                         f"not {check_kwargs['n_uniforms']}")
    wi = _env.unit(wi, "wi")
    m = phase_model(phase, channel=channel, variant=variant)
    return _core.check_phase(m.sample, m.eval, m.pdf, wi, **dict(check_kwargs, n_uniforms=PhaseModel.n_uniforms))
