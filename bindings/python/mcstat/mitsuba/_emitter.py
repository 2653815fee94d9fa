# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""A Mitsuba emitter, sampled by direction from a reference point, as the
callables of mcstat.check_emitter.

sample(u) is sample_direction(it, u) at the reference point: the
direction, channel ``channel`` of the weight (radiance / pdf) and the pdf
(a sample with pdf <= 0 or a weight 0 in every channel is a failed one).
eval(d) is the radiance arriving at the point along d, pdf(d) Mitsuba's
pdf_direction for the point the ray reaches.  An area light is looked at
in a scene holding its shape alone: visibility is the integrator's
business, not the emitter's sampler's.  An infinite light (envmap,
constant) is evaluated at the escaping direction.  Lights with a delta
position or direction (point, spot, directional) have no density over
directions and are refused.
"""
from __future__ import annotations

from typing import Any, Optional, Tuple

import numpy as np

from .. import _core
from . import _env


def _emitter_of(emitter: Any, variant: Optional[str]) -> Tuple[Any, Any, str, Any]:
    """(emitter, the scene to trace or None, variant, the object loaded)
    from a dict (an emitter, a shape holding one or a scene holding one) or
    a loaded Emitter, Shape or Scene.  The object loaded must be kept alive:
    an emitter's pointer to its shape does not own it."""
    mi, _ = _env.modules()
    if isinstance(emitter, dict):
        base = "Scene" if emitter.get("type") == "scene" else "Object"
        obj, v = _env.resolve(emitter, base, "emitter", variant)
    else:
        found = [(b, _env.variant_of(emitter, b)) for b in ("Emitter", "Shape", "Scene")]
        base = next((b for b, v_b in found if v_b is not None), "")
        if not base:
            raise TypeError(f"emitter: expected a Mitsuba Emitter, a Shape holding one or a Scene holding one "
                            f"(a plugin dict or a loaded object), got {type(emitter).__name__}")
        obj, v = _env.resolve(emitter, base, "emitter", variant)
    loaded = obj
    with _env.in_variant(v) as mi:
        if not isinstance(obj, (mi.Scene, mi.Shape, mi.Emitter)):
            raise TypeError(f"emitter: {emitter.get('type')!r} loads as a Mitsuba {_env.kind(mi, obj)}, not an "
                            "Emitter, a Shape holding one or a Scene")
        scene = obj if isinstance(obj, mi.Scene) else None
        if isinstance(obj, mi.Scene):
            ems = obj.emitters()
            if len(ems) != 1:
                raise ValueError(f"emitter: the scene holds {len(ems)} emitters; pass the one to check")
            obj = ems[0]
        elif isinstance(obj, mi.Shape):
            if obj.emitter() is None:
                raise ValueError("emitter: the shape holds no emitter")
            obj = obj.emitter()
        flags = int(obj.flags())
        if flags & int(mi.EmitterFlags.Delta):
            raise ValueError(f"emitter: {_env.class_name(obj)} has a delta position or direction: no density over "
                             "directions to check")
        if flags & int(mi.EmitterFlags.Infinite):
            return obj, None, v, loaded
        shape = obj.get_shape()
        if shape is None:
            raise ValueError(f"emitter: {_env.class_name(obj)} is neither infinite nor attached to a shape")
        if scene is None or len(scene.shapes()) != 1:  # the light's shape alone: no occluder
            scene = mi.load_dict({"type": "scene", "light": shape})
        return obj, scene, v, loaded


class EmitterModel:
    """A Mitsuba emitter seen from ``ref`` as ``sample(u)``, ``eval(d)`` and
    ``pdf(d)`` (the callables of `mcstat.check_emitter`)."""

    n_uniforms = 2

    def __init__(self, emitter: Any, ref: Any, *, channel: int = 0,
                 variant: Optional[str] = None) -> None:
        self.emitter, self.scene, self.variant, self._loaded = _emitter_of(emitter, variant)
        self.ref = np.asarray(ref, dtype=np.float64)
        if self.ref.shape != (3,) or not np.all(np.isfinite(self.ref)):
            raise ValueError(f"ref: a finite 3-vector, not {ref!r}")
        self.channel = int(channel)
        self.eval(np.array([[0.0, 0.0, 1.0]]))  # the channel exists

    def _it(self, mi: Any, width: int) -> Any:
        it = _env.zeros(self.variant, mi.Interaction3f, width)
        it.p = _env.constant(self.variant, mi.Point3f, self.ref)
        return it

    def sample(self, u: Any) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
        u = _env.uniforms(u, self.variant)
        ch = self.channel
        with _env.in_variant(self.variant) as mi:
            _, dr = _env.modules()

            def one(width: int, u2: Any) -> Tuple[Any, ...]:
                it = self._it(mi, width)
                ds, w = self.emitter.sample_direction(it, u2)
                return ds.d, _env.channel_of(w, ch, "the weight"), dr.all(w == 0.0), ds.pdf, ds, w, it

            d, weight, zero, pdf = _env.batch(self.variant, one, len(u), [(mi.Point2f, u[:, 0:2])], n_out=4)
        failed = zero | ~(pdf > 0)
        n = np.linalg.norm(d, axis=1)
        d = np.where(n[:, None] > 0, d / np.where(n > 0, n, 1.0)[:, None], d)  # float32 directions, renormalised
        return d, np.where(failed, 0.0, weight), np.where(failed, 0.0, pdf)

    def _at(self, which: str, d: Any) -> np.ndarray:
        d = np.asarray(d, dtype=np.float64).reshape(-1, 3)
        ch = self.channel
        with _env.in_variant(self.variant) as mi:
            _, dr = _env.modules()

            def one(width: int, v: Any) -> Tuple[Any, ...]:
                it = self._it(mi, width)
                if self.scene is None:  # infinite: what escapes along v
                    if which == "eval":
                        si = _env.zeros(self.variant, mi.SurfaceInteraction3f, width)
                        si.wi = -v
                        return _env.channel_of(self.emitter.eval(si), ch, "eval()"), si, it
                    ds = _env.zeros(self.variant, mi.DirectionSample3f, width)
                    ds.d = v
                    return self.emitter.pdf_direction(it, ds), ds, it
                si = self.scene.ray_intersect(mi.Ray3f(it.p, v))
                valid = si.is_valid()  # a masked-off lane is not zeroed by eval(): select
                if which == "eval":
                    return dr.select(valid, _env.channel_of(self.emitter.eval(si, valid), ch, "eval()"), 0.0), si, it
                ds = mi.DirectionSample3f(self.scene, si, it)
                return dr.select(valid, self.emitter.pdf_direction(it, ds, valid), 0.0), ds, si, it

            return _env.batch(self.variant, one, len(d), [(mi.Vector3f, d)], n_out=1)[0]

    def eval(self, d: Any) -> np.ndarray:
        return self._at("eval", d)

    def pdf(self, d: Any) -> np.ndarray:
        return self._at("pdf", d)


def emitter_model(emitter: Any, ref: Any, *, channel: int = 0,
                  variant: Optional[str] = None) -> EmitterModel:
    """The callables of a Mitsuba emitter seen from ``ref``: see `EmitterModel`."""
    return EmitterModel(emitter, ref, channel=channel, variant=variant)


def check_emitter(emitter: Any, ref: Any, *, channel: int = 0, variant: Optional[str] = None,
                  **check_kwargs: Any) -> _core.CheckReport:
    """mcstat.check_emitter on a Mitsuba emitter sampled by direction from
    the point ``ref`` (world space): ``check_emitter({"type": "rectangle",
    "emitter": {"type": "area"}}, ref=(0, 0, -1))``.

    ``emitter``: a plugin dict or loaded object of an emitter (an infinite
    one: envmap, constant), of a shape holding an area emitter, or of a
    scene holding one emitter.  ``check_kwargs`` go to
    `mcstat.check_emitter`; ``n_uniforms`` is Mitsuba's 2."""
    if "n_uniforms" in check_kwargs and check_kwargs["n_uniforms"] != EmitterModel.n_uniforms:
        raise ValueError(f"n_uniforms: Mitsuba's sample_direction takes {EmitterModel.n_uniforms} uniforms, "
                         f"not {check_kwargs['n_uniforms']}")
    m = emitter_model(emitter, ref, channel=channel, variant=variant)
    return _core.check_emitter(m.sample, m.eval, m.pdf, **dict(check_kwargs, n_uniforms=EmitterModel.n_uniforms))
