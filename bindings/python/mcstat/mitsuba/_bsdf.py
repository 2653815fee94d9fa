# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""A Mitsuba BSDF as the callables of mcstat.check_bsdf.

Failed samples.  Mitsuba marks a failed BSDF sample by a zero weight and
may leave bs.pdf > 0 (a rough conductor's microfacet sample reflected below
the horizon); mcstat wants pdf 0 and weight 0.  A sample whose weight is 0
in every channel, or whose pdf is not positive, is reported failed: the
rule of Mitsuba's own chi2 BSDFAdapter.  A BSDF black in every channel
(albedo 0) therefore fails every sample, and its check rejects on `mass`.
"""
from __future__ import annotations

from typing import Any, Optional, Tuple, Union

import numpy as np

from .. import _core
from . import _env
from ._lobes import Lobes, delta_lobes


class BSDFModel:
    """A Mitsuba BSDF as ``sample(wi, u)``, ``eval(wi, wo)``, ``pdf(wi, wo)``
    (the callables of `mcstat.check_bsdf`) and ``lobes(wi)`` (None for a
    BSDF without discrete lobes).

    ``eval`` is Mitsuba's eval(), which includes the cosine; the weight and
    eval are channel ``channel`` of Mitsuba's spectrum (each channel's
    weight is that channel's eval / pdf).  Directions are in the local
    shading frame (normal +z).  Each call sets the model's variant for its
    duration.
    """

    n_uniforms = 3  # sample1 (the component) and sample2

    def __init__(self, bsdf: Any, *, channel: int = 0, lobes: Union[str, Lobes, None] = "auto",
                 variant: Optional[str] = None) -> None:
        self.bsdf, self.variant = _env.resolve(bsdf, "BSDF", "bsdf", variant)
        self.channel = int(channel)
        with _env.in_variant(self.variant) as mi:
            self.ctx = mi.BSDFContext()
            self.flags = int(self.bsdf.flags())
            self.transmits = bool(self.flags & int(mi.BSDFFlags.Transmission))
            self.has_delta = bool(self.flags & int(mi.BSDFFlags.Delta))
            self.eval(np.array([0.0, 0.0, 1.0]), np.array([[0.0, 0.0, 1.0]]))  # the channel exists
        if isinstance(lobes, str):
            if lobes != "auto":
                raise ValueError(f"lobes: 'auto', None or a callable, not {lobes!r}")
            with _env.in_variant(self.variant):
                self.lobes: Optional[Lobes] = delta_lobes(self.bsdf, self.channel) if self.has_delta else None
        elif lobes is None or callable(lobes):
            self.lobes = lobes
        else:
            raise TypeError(f"lobes: 'auto', None or a callable, not {type(lobes).__name__}")

    def domain(self, wi: Any) -> str:
        """``"hemisphere"`` for a BSDF that only reflects, seen from above;
        ``"sphere"`` otherwise."""
        return "sphere" if self.transmits or not float(np.asarray(wi)[2]) > 0 else "hemisphere"

    def energy(self, wi: Any) -> bool:
        """Whether to ask albedo <= 1: always for a BSDF that only reflects,
        from above for one that transmits (radiance refracted out of the
        denser side is scaled by eta^2 > 1)."""
        return not self.transmits or float(np.asarray(wi)[2]) > 0

    def _si(self, mi: Any, width: int, wi: np.ndarray) -> Any:
        si = _env.zeros(self.variant, mi.SurfaceInteraction3f, width)
        si.wi = _env.constant(self.variant, mi.Vector3f, wi)
        return si

    def sample(self, wi: Any, u: Any) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
        wi = np.asarray(wi, dtype=np.float64)
        u = _env.uniforms(u, self.variant)
        ch = self.channel
        with _env.in_variant(self.variant) as mi:
            _, dr = _env.modules()

            def one(width: int, u0: Any, u12: Any) -> Tuple[Any, ...]:
                si = self._si(mi, width, wi)
                bs, w = self.bsdf.sample(self.ctx, si, u0, u12)
                return bs.wo, _env.channel_of(w, ch, "the weight"), dr.all(w == 0.0), bs.pdf, bs, w, si

            wo, weight, zero, pdf = _env.batch(self.variant, one, len(u),
                                               [(mi.Float, u[:, 0]), (mi.Point2f, u[:, 1:3])], n_out=4)
        failed = zero | ~(pdf > 0)
        n = np.linalg.norm(wo, axis=1)
        wo = np.where(n[:, None] > 0, wo / np.where(n > 0, n, 1.0)[:, None], wo)  # float32 directions, renormalised
        return wo, np.where(failed, 0.0, weight), np.where(failed, 0.0, pdf)

    def _at(self, which: str, wi: Any, wo: Any) -> np.ndarray:
        wi = np.asarray(wi, dtype=np.float64)
        wo = np.asarray(wo, dtype=np.float64).reshape(-1, 3)
        ch = self.channel
        with _env.in_variant(self.variant) as mi:

            def one(width: int, d: Any) -> Tuple[Any, ...]:
                si = self._si(mi, width, wi)
                if which == "pdf":
                    return self.bsdf.pdf(self.ctx, si, d), si
                v = self.bsdf.eval(self.ctx, si, d)
                return _env.channel_of(v, ch, "eval()"), v, si

            return _env.batch(self.variant, one, len(wo), [(mi.Vector3f, wo)], n_out=1)[0]

    def eval(self, wi: Any, wo: Any) -> np.ndarray:
        return self._at("eval", wi, wo)

    def pdf(self, wi: Any, wo: Any) -> np.ndarray:
        return self._at("pdf", wi, wo)


def bsdf_model(bsdf: Any, *, channel: int = 0, lobes: Union[str, Lobes, None] = "auto",
               variant: Optional[str] = None) -> BSDFModel:
    """The callables of a Mitsuba BSDF (a plugin dict, loaded with
    mi.load_dict, or a loaded object): see `BSDFModel`."""
    return BSDFModel(bsdf, channel=channel, lobes=lobes, variant=variant)


def check_bsdf(bsdf: Any, wi: Any, *, channel: int = 0, lobes: Union[str, Lobes, None] = "auto",
               variant: Optional[str] = None, **check_kwargs: Any) -> _core.CheckReport:
    """mcstat.check_bsdf on a Mitsuba BSDF: ``check_bsdf({"type":
    "roughconductor", "alpha": 0.2}, wi)``.

    ``bsdf`` is a plugin dict or a loaded Mitsuba BSDF; ``wi`` the incident
    direction in the local shading frame (normal +z), normalised here.
    ``lobes="auto"`` gives a BSDF with discrete (delta) lobes the lobes
    written from the physics (`delta_lobes`); pass your own callable, or
    None.  By default the domain is the upper hemisphere for a BSDF that
    only reflects, seen from above, else the sphere; ``energy`` (albedo <= 1)
    is asked unless the BSDF transmits and wi is below the surface.
    ``check_kwargs`` go to `mcstat.check_bsdf` (``n``, ``seed``, ``alpha``,
    ``domain``, ``energy``, ``routes``...); ``n_uniforms`` is Mitsuba's 3.
    """
    if "n_uniforms" in check_kwargs and check_kwargs["n_uniforms"] != BSDFModel.n_uniforms:
        raise ValueError(f"n_uniforms: a Mitsuba BSDF takes {BSDFModel.n_uniforms} uniforms, "
                         f"not {check_kwargs['n_uniforms']}")
    wi = _env.unit(wi, "wi")
    m = bsdf_model(bsdf, channel=channel, lobes=lobes, variant=variant)
    kw = dict(check_kwargs, n_uniforms=BSDFModel.n_uniforms)
    kw.setdefault("domain", m.domain(wi))
    kw.setdefault("energy", m.energy(wi))
    if m.lobes is not None:
        kw["lobes"] = m.lobes
    return _core.check_bsdf(m.sample, m.eval, m.pdf, wi, **kw)

