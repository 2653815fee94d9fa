# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""A Mitsuba medium's free flights along a ray as the callables of
mcstat.check_medium.

sample(u) tracks a flight as Mitsuba's volumetric path tracer does (delta
tracking): tentative collisions from the medium's sample_interaction
(against its majorant), each real with probability sigma_t / majorant,
the flight continuing from a null collision.  A real collision at t <
tmax reports pdf(t) and the weight sigma_s / sigma_t there; a flight that
passes tmax (a surface) is an escape: pdf 0 and weight 1, checked
against T(tmax) (check_medium's escape_transmittance=).  A flight needs a random
number of uniforms: it gets two from mcstat and derives the rest by
splitmix64, so each flight is a pure function of its two uniforms.

The claims come from the medium's coefficients, not its sampler:
pdf(t) = sigma_t(t) T(t) and eval(t) = sigma_s(t) T(t), sigma from
get_scattering_coefficients at the point, T = exp(-tau) from the optical
depth tau tabulated along the ray (trapezoids on ``table`` points: exact
for a homogeneous medium, within ~1e-8 on a trilinear grid, whose sigma_t
is piecewise linear along a ray).
"""
from __future__ import annotations

from typing import Any, Optional, Tuple

import numpy as np

from .. import _core
from . import _env

_MASK64 = np.uint64(0xFFFFFFFFFFFFFFFF)
MAX_COLLISIONS = 100_000  # null collisions of one flight before it is declared stuck


def _splitmix(x: np.ndarray) -> np.ndarray:
    with np.errstate(over="ignore"):
        x = x + np.uint64(0x9E3779B97F4A7C15)
        x = (x ^ (x >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
        x = (x ^ (x >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
        out: np.ndarray = x ^ (x >> np.uint64(31))
        return out


class MediumModel:
    """A Mitsuba medium's flights along the ray from ``origin`` along
    ``direction`` up to a surface at ``tmax`` as ``sample(u)``, ``eval(t)``
    and ``pdf(t)`` (the callables of `mcstat.check_medium`), channel
    ``channel`` of its coefficients.  ``sigma_ref`` (the mean sigma_t along
    the ray) and ``transmittance`` (T(tmax)) are check_medium's arguments
    (sigma_ref and escape_transmittance)."""

    n_uniforms = 2

    def __init__(self, medium: Any, *, origin: Any = (0.5, 0.5, 0.0), direction: Any = (0.0, 0.0, 1.0),
                 tmax: float = 1.0, channel: int = 0, table: Optional[int] = None,
                 variant: Optional[str] = None) -> None:
        self.medium, self.variant = _env.resolve(medium, "Medium", "medium", variant)
        self.origin = np.asarray(origin, dtype=np.float64)
        if self.origin.shape != (3,) or not np.all(np.isfinite(self.origin)):
            raise ValueError(f"origin: a finite 3-vector, not {origin!r}")
        self.direction = _env.unit(direction, "direction")
        self.tmax = float(tmax)
        if not (np.isfinite(self.tmax) and self.tmax > 0):
            raise ValueError(f"tmax: a finite distance > 0, not {tmax!r}")
        self.channel = int(channel)
        with _env.in_variant(self.variant):
            self.homogeneous = bool(self.medium.is_homogeneous())
        self._constant: Optional[Tuple[float, float]] = None
        if self.homogeneous:  # its coefficients once: the scalar variants' loops skip them
            s, st = self._coefficients(np.zeros(1))
            self._constant = (float(s[0]), float(st[0]))
        if table is None:
            table = 2 if self.homogeneous else 40001
        if int(table) < 2:
            raise ValueError(f"table: at least 2 points, not {table!r}")
        self.z = np.linspace(0.0, self.tmax, int(table))
        self.sig_t = self._coefficients(self.z)[1]
        self.tau = np.concatenate([[0.0], np.cumsum(0.5 * (self.sig_t[1:] + self.sig_t[:-1]) * np.diff(self.z))])
        self.transmittance = float(np.exp(-self.tau[-1]))
        self.sigma_ref = float(self.tau[-1] / self.tmax)
        if not self.sigma_ref > 0:
            raise ValueError("medium: sigma_t is 0 along the ray: no collision to check (move origin=, direction=)")

    def _coefficients(self, t: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
        """(sigma_s, sigma_t) at the distances t along the ray."""
        if self._constant is not None:
            return np.full(len(t), self._constant[0]), np.full(len(t), self._constant[1])
        p = self.origin[None, :] + np.asarray(t, dtype=np.float64)[:, None] * self.direction[None, :]
        ch = self.channel
        with _env.in_variant(self.variant) as mi:

            def one(width: int, x: Any) -> Tuple[Any, ...]:
                mei = _env.zeros(self.variant, mi.MediumInteraction3f, width)
                mei.p = x
                mei.wi = -mi.Vector3f(*[float(c) for c in self.direction])
                sigma_s, _, sigma_t = self.medium.get_scattering_coefficients(mei, True)
                return _env.channel_of(sigma_s, ch, "sigma_s"), _env.channel_of(sigma_t, ch, "sigma_t"), mei

            s, st = _env.batch(self.variant, one, len(p), [(mi.Point3f, p)], n_out=2)
        return s, st

    def _tau(self, t: np.ndarray) -> np.ndarray:
        """The optical depth at t: the table's trapezoids, the last one partial."""
        z, sig = self.z, self.sig_t
        i = np.clip(np.searchsorted(z, t, side="right") - 1, 0, len(z) - 2)
        f = (t - z[i]) / (z[i + 1] - z[i])
        s = sig[i] + f * (sig[i + 1] - sig[i])
        tau: np.ndarray = self.tau[i] + (t - z[i]) * 0.5 * (sig[i] + s)
        return tau

    def _claims(self, t: Any) -> Tuple[np.ndarray, np.ndarray]:
        """(pdf, eval) at the distances t: sigma_t T and sigma_s T before tmax, 0 beyond."""
        t = np.asarray(t, dtype=np.float64)
        if len(t) == 0:
            return np.zeros(0), np.zeros(0)
        inside = (t >= 0) & (t < self.tmax)
        tt = np.where(inside, t, 0.0)
        s, st = self._coefficients(tt)
        T = np.exp(-self._tau(tt))
        return np.where(inside, st * T, 0.0), np.where(inside, s * T, 0.0)

    def pdf(self, t: Any) -> np.ndarray:
        return self._claims(t)[0]

    def eval(self, t: Any) -> np.ndarray:
        return self._claims(t)[1]

    def _uniform(self, key: np.ndarray, j: int) -> np.ndarray:
        bits = _splitmix(key ^ _splitmix(np.full(key.shape, j, dtype=np.uint64)))
        return _env.uniforms((bits >> np.uint64(11)).astype(np.float64) * 2.0 ** -53, self.variant)

    def sample(self, u: Any) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
        u = np.asarray(u, dtype=np.float64)
        k = len(u)
        key = ((np.floor(u[:, 0] * 2.0 ** 32).astype(np.uint64) << np.uint64(32))
               | np.floor(u[:, 1] * 2.0 ** 32).astype(np.uint64))
        t = np.zeros(k)            # where each flight stands
        hit = np.full(k, np.nan)   # its real collision (nan: escaped)
        weight = np.zeros(k)
        active = np.ones(k, dtype=bool)
        ch, d = self.channel, self.direction
        with _env.in_variant(self.variant) as mi:
            def tentative(width: int, o: Any, maxt: Any, xi: Any) -> Tuple[Any, ...]:
                ray = mi.Ray3f(o, mi.Vector3f(*[float(c) for c in d]))
                ray.maxt = maxt
                mei = self.medium.sample_interaction(ray, xi, ch, True)
                return (mei.t, mei.is_valid(), _env.channel_of(mei.sigma_t, ch, "sigma_t"),
                        _env.channel_of(mei.combined_extinction, ch, "the majorant"),
                        _env.channel_of(mei.sigma_s, ch, "sigma_s"), mei, ray)

            for j in range(MAX_COLLISIONS):
                idx = np.flatnonzero(active)
                if len(idx) == 0:
                    break
                o = self.origin[None, :] + t[idx, None] * d[None, :]
                maxt = self.tmax - t[idx]
                mt, valid, st, maj, ss = _env.batch(self.variant, tentative, len(idx), [
                    (mi.Point3f, o), (mi.Float, maxt), (mi.Float, self._uniform(key[idx], 2 * j))], n_out=5)
                escaped = ~(valid & (mt < maxt))
                weight[idx[escaped]] = 1.0  # passed the surface: the throughput it carries on (analog: 1)
                xi2 = self._uniform(key[idx], 2 * j + 1)
                with np.errstate(divide="ignore", invalid="ignore"):
                    real = ~escaped & (xi2 < st / maj)
                    w = ss / st
                hit[idx[real]] = t[idx[real]] + mt[real]
                weight[idx[real]] = w[real]
                t[idx[~escaped]] += mt[~escaped]
                active[idx[escaped | real]] = False
            else:
                raise RuntimeError(f"medium: {int(active.sum())} flights still tracking after {MAX_COLLISIONS} "
                                   "null collisions (a majorant far above sigma_t?)")
        real = ~np.isnan(hit)
        pdf = np.zeros(k)
        pdf[real] = self.pdf(hit[real])
        return np.where(real, hit, 0.0), weight, pdf


def medium_model(medium: Any, **kwargs: Any) -> MediumModel:
    """The callables of a Mitsuba medium (plugin dict or loaded): see `MediumModel`."""
    return MediumModel(medium, **kwargs)


def check_medium(medium: Any, *, origin: Any = (0.5, 0.5, 0.0), direction: Any = (0.0, 0.0, 1.0), tmax: float = 1.0,
                 channel: int = 0, table: Optional[int] = None, variant: Optional[str] = None,
                 **check_kwargs: Any) -> _core.CheckReport:
    """mcstat.check_medium on a Mitsuba medium: ``check_medium({"type":
    "homogeneous", "sigma_t": 2.0, "albedo": 0.75}, tmax=1.0)``.

    Flights along the ray from ``origin`` along ``direction`` (world space;
    the default crosses the unit cube a grid volume fills by default) to a
    surface at ``tmax``, tracked by delta tracking over the medium's
    sample_interaction (`MediumModel`).  ``sigma_ref`` defaults to the mean
    sigma_t along the ray and ``escape_transmittance`` to T(tmax);
    ``check_kwargs`` go to `mcstat.check_medium`."""
    if "n_uniforms" in check_kwargs and check_kwargs["n_uniforms"] != MediumModel.n_uniforms:
        raise ValueError(f"n_uniforms: a flight takes {MediumModel.n_uniforms} uniforms here, "
                         f"not {check_kwargs['n_uniforms']}")
    m = medium_model(medium, origin=origin, direction=direction, tmax=tmax, channel=channel, table=table,
                     variant=variant)
    kw = dict(check_kwargs, n_uniforms=MediumModel.n_uniforms)
    kw.setdefault("sigma_ref", m.sigma_ref)
    if "transmittance" not in kw:  # (the deprecated name, passed on as given)
        kw.setdefault("escape_transmittance", m.transmittance)
    return _core.check_medium(m.sample, m.eval, m.pdf, **kw)
