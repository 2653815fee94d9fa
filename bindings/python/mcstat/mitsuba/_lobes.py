# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""The discrete (delta) lobes of Mitsuba's smooth BSDFs, for check_bsdf's lobes=.

Each lobe is (direction, mass, value): mass the probability that sample()
returns it (what it must report as its pdf), value its albedo (the
integral of f |cos| over it), so that the weight must be value / mass.
They are written from the physics and from the sampling choices Mitsuba
documents, with the BSDF's parameters read by mi.traverse, never from the
sampler's output:

- dielectric: reflection with the unpolarised Fresnel reflectance F of the
  relative index eta, refraction (Snell) with 1 - F, picked with those
  probabilities; the refraction's value is (1 - F) / eta_it^2 (radiance
  transport: radiance entering the denser side is compressed), times
  specular_transmittance; the reflection's F times specular_reflectance;
- thindielectric: reflection R = 2F / (1 + F) (the sheet's internal
  reflections summed) and straight transmission 1 - R;
- conductor: the mirror, mass 1, value the conductor's Fresnel reflectance
  of the complex index eta + i k, times specular_reflectance;
- plastic: the specular coat, picked with probability F w / (F w +
  (1 - F)(1 - w)), w = s / (s + d) from the mean specular and diffuse
  reflectances; its value F times specular_reflectance;
- mask: straight transmission -wi with mass and value 1 - opacity (over a
  nested BSDF without delta lobes).

One-sided BSDFs (conductor, plastic) seen from below have no lobe.
Textures must be constant (a 'value' parameter): a spatially varying one,
a BSDF wrapped in another (twosided, blendbsdf) or another delta BSDF
raises ValueError asking for lobes= written by the caller.
"""
from __future__ import annotations

from typing import Any, Callable, Dict, List, Tuple

import numpy as np

from . import _env

Lobes = Callable[[np.ndarray], Tuple[np.ndarray, np.ndarray, np.ndarray]]

KNOWN = {"SmoothDielectric": "dielectric", "ThinDielectric": "thindielectric", "SmoothConductor": "conductor",
         "SmoothPlastic": "plastic", "MaskBSDF": "mask", "Mask": "mask"}  # Mask: 3.6's name


def fresnel(cos_i: float, eta: float) -> Tuple[float, float, float]:
    """Unpolarised Fresnel reflectance of a dielectric interface of relative
    index eta, the refracted cosine and eta_it (eta seen from wi's side)."""
    eta_it = eta if cos_i > 0 else 1.0 / eta
    c = abs(cos_i)
    s2t = (1.0 - c * c) / (eta_it * eta_it)
    if s2t >= 1.0:
        return 1.0, 0.0, eta_it
    ct = float(np.sqrt(1.0 - s2t))
    rs = (c - eta_it * ct) / (c + eta_it * ct)
    rp = (eta_it * c - ct) / (eta_it * c + ct)
    return 0.5 * (rs * rs + rp * rp), ct, eta_it


def fresnel_conductor(c: float, eta: float, k: float) -> float:
    """Unpolarised reflectance of a conductor of complex index eta + i k."""
    n = complex(eta, k)
    ct = np.sqrt(1 - (1 - c * c) / (n * n))
    rs = (c - n * ct) / (c + n * ct)
    rp = (n * c - ct) / (n * c + ct)
    return float(0.5 * (abs(rs) ** 2 + abs(rp) ** 2))


def _mirror(wi: np.ndarray) -> List[float]:
    return [-float(wi[0]), -float(wi[1]), float(wi[2])]


def _out(dirs: List[List[float]], mass: List[float], value: List[float]) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    return (np.array(dirs, dtype=np.float64).reshape(-1, 3), np.array(mass, dtype=np.float64),
            np.array(value, dtype=np.float64))


def dielectric(eta: float, reflectance: float = 1.0, transmittance: float = 1.0) -> Lobes:
    def lobes(wi: np.ndarray) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
        F, ct, eta_it = fresnel(float(wi[2]), eta)
        if F >= 1.0:
            return _out([_mirror(wi)], [1.0], [reflectance])
        t = [-float(wi[0]) / eta_it, -float(wi[1]) / eta_it, -float(np.sign(wi[2])) * ct]
        return _out([_mirror(wi), t], [F, 1 - F], [F * reflectance, (1 - F) / eta_it ** 2 * transmittance])
    return lobes


def thindielectric(eta: float, reflectance: float = 1.0, transmittance: float = 1.0) -> Lobes:
    def lobes(wi: np.ndarray) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
        F = fresnel(abs(float(wi[2])), eta)[0]
        R = 2 * F / (1 + F) if F < 1 else 1.0
        if R >= 1.0:
            return _out([_mirror(wi)], [1.0], [reflectance])
        return _out([_mirror(wi), [-float(c) for c in wi]], [R, 1 - R], [R * reflectance, (1 - R) * transmittance])
    return lobes


def conductor(eta: float, k: float, reflectance: float = 1.0) -> Lobes:
    def lobes(wi: np.ndarray) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
        if not wi[2] > 0:
            return _out([], [], [])
        return _out([_mirror(wi)], [1.0], [fresnel_conductor(float(wi[2]), eta, k) * reflectance])
    return lobes


def plastic(eta: float, specular: float, specular_mean: float, diffuse_mean: float) -> Lobes:
    w = specular_mean / (specular_mean + diffuse_mean)

    def lobes(wi: np.ndarray) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
        if not wi[2] > 0:
            return _out([], [], [])
        F = fresnel(float(wi[2]), eta)[0]
        p = F * w / (F * w + (1 - F) * (1 - w))
        return _out([_mirror(wi)], [p], [F * specular])
    return lobes


def mask(opacity: float) -> Lobes:
    def lobes(wi: np.ndarray) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
        return _out([[-float(c) for c in wi]], [1 - opacity], [1 - opacity])
    return lobes


def _params(bsdf: Any) -> Dict[str, Any]:
    import mitsuba as mi

    p = mi.traverse(bsdf)
    return {k: p[k] for k in p.keys()}  # type: ignore[no-untyped-call]


def _constant(params: Dict[str, Any], name: str, channel: int, default: float, kind: str) -> Tuple[float, float]:
    """(channel's value, mean over channels) of the constant texture ``name``."""
    others = [k for k in params if k.startswith(name + ".") and k != name + ".value"]
    if others:
        raise ValueError(f"bsdf: the {kind}'s {name} is not a constant texture ({', '.join(others)}): "
                         "pass lobes= written for it")
    key = name + ".value" if name + ".value" in params else name
    if key not in params:
        return default, default
    v = _values(params[key])
    return float(v[min(channel, len(v) - 1)]), float(np.mean(v))


def _values(x: Any) -> np.ndarray:
    """A parameter (a float, a Dr.Jit scalar or colour of any variant) as a flat float64 array."""
    return np.atleast_1d(np.array(x, dtype=np.float64)).ravel()


def delta_lobes(bsdf: Any, channel: int = 0) -> Lobes:
    """The lobes(wi) of a loaded Mitsuba BSDF with discrete lobes (in the
    variant it was loaded in): dielectric, thindielectric, conductor,
    plastic, mask.  ValueError for another one."""
    name = _env.class_name(bsdf)
    kind = KNOWN.get(name)
    if kind is None:
        if name == "BSDF":  # a Python plugin: its to_string() names it
            name = (str(bsdf).splitlines() or [name])[0]
        raise ValueError(f"bsdf: {name} has discrete (delta) lobes that mcstat.mitsuba cannot derive (it knows "
                         f"{', '.join(sorted(KNOWN.values()))}): pass lobes=, a callable wi -> (directions, "
                         "mass, value), or lobes=None to check its smooth part alone")
    p = _params(bsdf)
    if kind == "mask":
        import mitsuba as mi

        nested = [k for k in p if k.startswith("nested_bsdf.")]
        if int(bsdf.flags()) & int(mi.BSDFFlags.DeltaReflection | mi.BSDFFlags.DeltaTransmission):
            raise ValueError("bsdf: a mask over a BSDF with delta lobes: pass lobes= (nested parameters: "
                             f"{', '.join(nested)})")
        return mask(_constant(p, "opacity", channel, 1.0, kind)[0])
    if kind == "conductor":
        return conductor(_constant(p, "eta", channel, 0.0, kind)[0], _constant(p, "k", channel, 1.0, kind)[0],
                         _constant(p, "specular_reflectance", channel, 1.0, kind)[0])
    eta = float(_values(p["eta"])[0])
    spec, spec_mean = _constant(p, "specular_reflectance", channel, 1.0, kind)
    if kind == "plastic":
        return plastic(eta, spec, spec_mean, _constant(p, "diffuse_reflectance", channel, 0.5, kind)[1])
    trans = _constant(p, "specular_transmittance", channel, 1.0, kind)[0]
    return (dielectric if kind == "dielectric" else thindielectric)(eta, spec, trans)
