# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""Renderers' own EXR outputs for ``mcstat image-test``.

One ``.exr`` given alone for a side is read by its channel names:

===============  ==============================  ===============================  ===========================
renderer         channels                        meaning                          n (samples per pixel)
===============  ==============================  ===============================  ===========================
Mitsuba 3        ``P.X P.Y P.Z`` and             per pixel, the means of f and    ``--spp`` (the EXR does not
``moment``       ``m2_P.X m2_P.Y m2_P.Z``        f^2 over the pixel's samples     hold it); box filter only
integrator       (``P`` the nested integrator's  (CIE XYZ of the nested
                 name, e.g. ``nested``)          integrator's radiance)
several seeds    ``seed<K>.<C>``, e.g.           seed K's render, channel C       the number of seeds
in one EXR       ``seed0.R seed0.G seed0.B
                 seed1.R ...``
Arnold           ``*_variance*`` / ``variance``  refused (see below)
Cycles           ``Debug Sample Count``          refused (see below)
===============  ==============================  ===============================  ===========================

Any other single EXR is one seed's image (several are needed per side).

**Mitsuba 3's moment integrator** (``{'type': 'moment', 'nested': {...}}``)
writes, for each nested integrator ``P``, the AOVs ``P.X``, ``P.Y``,
``P.Z`` (the sample's radiance converted to CIE XYZ) and ``m2_P.X`` ...
(their squares); the film develops every AOV as sum(w f) / sum(w) over the
samples it received.  With ``'rfilter': {'type': 'box'}`` (radius 0.5)
each sample falls in one pixel with weight 1, so the file holds m1 =
mean(f) and m2 = mean(f^2) over the pixel's spp samples, and the summary
is n = spp, mean = m1, M2 = n (m2 - m1^2).  With any other filter (Mitsuba's
default is ``gaussian``) a pixel holds weighted means of samples shared
with its neighbours: n is not the spp, m2 - m1^2 is the weighted spread of
the samples in the footprint, not the variance of the pixel's estimate,
and neighbouring pixels are correlated; the test is then not valid.  The
EXR does not record the filter: rendering with a box filter is the user's
part.  The channels tested are X, Y, Z (``--channels rgb``) or Y, the
luminance (``--channels luminance``).

**float32 cancellation.** m1 and m2 are float32.  If each carries a
relative error of at most k u (u = 2^-24 per rounding, 2^-11 for half
channels), the computed v = m2 - m1^2 is off by at most
k u (m2 + 2 m1^2) (first order: dv = dm2 - 2 m1 dm1).  The film sums the
spp values in float32 before dividing, whose error grows like sqrt(n)
rounding errors (worst case n), so k = 1 + sqrt(n) (the final rounding
plus the sum's).  A pixel channel is not tested ("variance lost to float32
cancellation") when v <= 10 k u (m2 + 2 m1^2), i.e. when the rounding
error could exceed a tenth of the variance, and always when v <= 0 with
m2 > 0.  The count is reported in the comparison's notes.

**Several seeds in one EXR**: layers named ``seed<K>`` (K = 0, 1, ...;
read in numerical order), each with the same channels, ordered R, G, B, A
or Y or else by name.

**Refused, with the reason:** Arnold's ``variance`` filter AOVs (e.g.
``RGBA_variance``, written for the Arnold denoiser noice): Arnold documents
them as the variance information the denoiser needs, not whether they are
the variance of the samples or of the pixel's estimate, with which
normalisation (n or n - 1) and filter weights, and the file holds no
sample count (the same holds for the ``Denoising Variance`` pass of
Cycles 2.8x).  Blender Cycles (3.0 and later) writes no variance pass; its
``Debug Sample Count`` pass (adaptive sampling) holds each pixel's sample
count (as a fraction of the maximum) but no second moment.  Render one
image per seed instead (or several seeds' layers in one EXR).

The ASWF ``OpenEXR`` package reads the files; without it a
`MissingReaderError` says so.
"""
from __future__ import annotations

import re
from typing import Dict, Iterable, List, Optional, Tuple

import numpy as np

from mcstat.image import ImageInputError, Samples, Summary

from .errors import require

__all__ = ["kind_of", "read_moment", "read_seed_layers", "cancellation_mask", "EPS_FLOAT32", "EPS_HALF",
           "CANCELLATION_FACTOR"]

EPS_FLOAT32 = 2.0 ** -24
EPS_HALF = 2.0 ** -11
# the variance is kept when the rounding error may reach at most 1/10 of it
CANCELLATION_FACTOR = 10.0

_SEED = re.compile(r"^seed(\d+)\.(.+)$")
_ORDER = ("X", "Y", "Z", "R", "G", "B", "A")


def _openexr(path: str):
    from .image import MissingReaderError  # defined there (the module imports this one)

    return require("OpenEXR", f"{path}: reading EXR", MissingReaderError)


def _header_channels(path: str) -> List[str]:
    OpenEXR = _openexr(path)
    try:
        with OpenEXR.File(path, header_only=True) as f:
            return [c.name for c in f.header()["channels"]]
    except Exception as e:  # OpenEXR raises plain exceptions for unreadable files
        raise ImageInputError(f"{path}: cannot read EXR: {e}") from e


def _channels(path: str) -> Dict[str, np.ndarray]:
    """Every channel of the file's first part, each (H, W), separately."""
    OpenEXR = _openexr(path)
    try:
        with OpenEXR.File(path, separate_channels=True) as f:
            return {k: np.asarray(v.pixels) for k, v in f.channels().items()}
    except Exception as e:
        raise ImageInputError(f"{path}: cannot read EXR: {e}") from e


def kind_of(path: str) -> str:
    """The input kind of one EXR file, from its channel names."""
    names = _header_channels(path)
    if any(n.startswith("m2_") for n in names):
        return "exr-moment"
    if any(_SEED.match(n) for n in names):
        return "exr-seeds"
    low = [n.lower() for n in names]
    if any("variance" in n for n in low):
        raise ImageInputError(
            f"{path}: variance AOVs ({', '.join(n for n in names if 'variance' in n.lower())}): neither Arnold's "
            "variance filter nor Cycles' former (2.8x) 'Denoising Variance' pass documents whether it is the "
            "variance of the samples or of the pixel's estimate, its normalisation or filter weights, and the "
            "file holds no sample count; render one image per seed instead")
    if any("sample count" in n for n in low):
        raise ImageInputError(
            f"{path}: a sample-count pass without a second moment (Cycles writes no variance pass) gives no "
            "per-pixel variance; render one image per seed instead")
    return "images"


def _sorted_channels(names: Iterable[str]) -> List[str]:
    return sorted(names, key=lambda c: (_ORDER.index(c) if c in _ORDER else len(_ORDER), c))


def cancellation_mask(m1: np.ndarray, m2: np.ndarray, n: np.ndarray, eps: float = EPS_FLOAT32) -> np.ndarray:
    """True where m2 - m1^2 (in float64 from the stored values) is within
    the rounding error of stored moments (see the module's doc)."""
    v = m2 - m1 * m1
    bound = CANCELLATION_FACTOR * (1.0 + np.sqrt(n)) * eps * (np.abs(m2) + 2.0 * m1 * m1)
    return ((m2 > 0) | (m1 != 0)) & (v <= bound)


def read_moment(path: str, spp: Optional[int]) -> Summary:
    """Mitsuba 3's moment-integrator EXR as per-pixel summaries (n = spp)."""
    if spp is None:
        raise ImageInputError(f"{path}: Mitsuba's moment AOVs hold no sample count: give the samples per pixel "
                              "(--spp N, the render's spp)")
    if int(spp) != spp or spp < 2:
        raise ImageInputError(f"{path}: spp must be an integer >= 2, got {spp}")
    ch = _channels(path)
    prefixes = sorted({n[3:].rsplit(".", 1)[0] for n in ch if n.startswith("m2_") and "." in n})
    if len(prefixes) != 1:
        raise ImageInputError(f"{path}: expected the moment AOVs of one nested integrator (m2_<name>.X ...), "
                              f"found {prefixes or 'none'}")
    p = prefixes[0]
    comps = _sorted_channels({n[len(p) + 4:] for n in ch if n.startswith(f"m2_{p}.")} |
                             {n[len(p) + 1:] for n in ch if n.startswith(f"{p}.")})
    m1s, m2s, eps = [], [], EPS_FLOAT32
    for c in comps:
        for name in (f"{p}.{c}", f"m2_{p}.{c}"):
            if name not in ch:
                raise ImageInputError(f"{path}: channel {name!r} is missing (the moment integrator writes "
                                      f"{p}.C and m2_{p}.C for each C)")
            if ch[name].dtype == np.float16:
                eps = EPS_HALF
        m1s.append(ch[f"{p}.{c}"])
        m2s.append(ch[f"m2_{p}.{c}"])
    m1 = np.stack(m1s, axis=-1).astype(np.float64)
    m2 = np.stack(m2s, axis=-1).astype(np.float64)
    n = np.full(m1.shape, float(spp))
    lost = cancellation_mask(m1, m2, n, eps)
    big_m2 = np.where(lost, 0.0, n * (m2 - m1 * m1))
    return Summary(n, m1, big_m2, list(comps), unreliable=lost)


def read_seed_layers(path: str) -> Samples:
    """One EXR whose layers ``seed<K>`` are the seeds' renders."""
    ch = _channels(path)
    seeds: Dict[int, Dict[str, np.ndarray]] = {}
    for name, a in ch.items():
        m = _SEED.match(name)
        if m:
            seeds.setdefault(int(m.group(1)), {})[m.group(2)] = a
    ks = sorted(seeds)
    comps = _sorted_channels(seeds[ks[0]])
    for k in ks:
        missing = [c for c in comps if c not in seeds[k]]
        extra = [c for c in seeds[k] if c not in comps]
        if missing or extra:
            bad = f"seed{k}.{(missing or extra)[0]}"
            raise ImageInputError(f"{path}: channel {bad!r} is {'missing' if missing else 'unexpected'}: every "
                                  f"seed layer must hold the channels {comps} of seed{ks[0]}")
    data = np.stack([np.stack([seeds[k][c] for c in comps], axis=-1) for k in ks])
    return Samples(data, list(comps))


def spp_pair(spp) -> Tuple[Optional[int], Optional[int]]:
    """``--spp N`` (both sides) or ``--spp REF CAND``."""
    if spp is None:
        return None, None
    if isinstance(spp, (int, np.integer)):
        return int(spp), int(spp)
    s = list(spp)
    if len(s) == 1:
        return s[0], s[0]
    if len(s) == 2:
        return s[0], s[1]
    raise ImageInputError(f"spp: one value (both sides) or two (reference, candidate), got {s}")
