# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""Image files for ``mcstat image-test``: the readers, the significance map, the command.

The comparison itself is the library's (`mcstat.image.compare`); this
module reads its inputs from files and writes its outputs.

Inputs, per side (`load_side`):

- one ``.npy`` array with a seeds axis: ``(seeds, H, W)`` or ``(seeds, H,
  W, C)`` (``seed_axis`` says where the seeds are: ``-1`` for ``(H, W,
  seeds)``; left out, the shapes must settle it, as ``mcstat.image.compare``
  says, else the stack is refused as ambiguous);
- several image files, one per seed: ``.exr`` (the ASWF ``OpenEXR``
  package), ``.pfm`` (read here: Pillow reads only grey PFM), ``.npy``
  holding one ``(H, W[, C])`` image;
- one ``.npz`` of per-pixel summaries: ``n``, ``mean`` and ``M2`` (the sum
  of squared deviations) or ``var`` (``M2 / (n - 1)``), each ``(H, W)`` or
  ``(H, W, C)``; ``n`` may be a scalar;
- one ``.npz`` of per-pixel accumulators (a render farm's merged
  ``mcstat.MomentsArray``, written by ``mcstat.image.save_moments``): the
  key ``moments``, a ``uint8`` array ``(H, W[, C], 96)`` of libmcstat's
  96-byte records, each checked (magic, version, checksum) when read;
- one ``.exr`` holding a renderer's own per-pixel output, told apart by
  its channel names (`mcstat_app.image_exr`): Mitsuba 3's ``moment``
  integrator (``P.X`` ... and ``m2_P.X`` ...; the samples per pixel from
  ``spp``, a box reconstruction filter required), or several seeds as
  layers ``seed0.R``, ``seed0.G``, ... ``seed1.R`` ...; Arnold's variance
  AOVs and Cycles' sample-count pass are refused with the reason.

Each input kind is one reader function in ``_READERS`` returning
`Samples` or `Summary`.  The significance map's colours are
``mcstat.image.COLOR_KEY``.
"""
from __future__ import annotations

import json
import os
import time
import zipfile
import zlib
from typing import Callable, Dict, List, Optional, Sequence, Union

import numpy as np

from mcstat import MomentsArray
from mcstat.image import (
    COLOR_KEY,
    ImageComparison,
    ImageInputError,
    Samples,
    Side,
    Summary,
    _channel_names,
    _seed_axis_of,
    summary_of_moments,
)
from mcstat.image import compare as _compare

from . import image_exr
from .errors import MissingPackageError, OutputError, require

__all__ = ["load_side", "read_image", "compare", "map_rgb", "write_map", "run", "ImageInputError",
           "MissingReaderError"]


class MissingReaderError(MissingPackageError, ImageInputError):
    """An input whose reader package is not installed (OpenEXR for .exr)."""


# what numpy and zipfile raise on a corrupt or truncated file
_READ_ERRORS = (OSError, ValueError, EOFError, zipfile.BadZipFile, zlib.error, KeyError)


# ---- readers -----------------------------------------------------------------
def _as_hwc(img: np.ndarray, path: str) -> np.ndarray:
    if img.ndim == 2:
        return img[:, :, None]
    if img.ndim == 3:
        return img
    raise ImageInputError(f"{path}: an image must be (H, W) or (H, W, C), got shape {img.shape}")


def _read_pfm(path: str) -> np.ndarray:
    """Portable float map: "PF" (RGB) or "Pf" (grey), width height, scale
    (negative: little-endian), rows bottom to top."""
    with open(path, "rb") as f:
        tokens: List[bytes] = []
        while len(tokens) < 4:
            line = f.readline()
            if not line:
                raise ImageInputError(f"{path}: truncated PFM header")
            tokens += line.split()
        kind, w, h, scale = tokens[0], int(tokens[1]), int(tokens[2]), float(tokens[3])
        if kind not in (b"PF", b"Pf") or w <= 0 or h <= 0 or scale == 0:
            raise ImageInputError(f"{path}: not a PFM file")
        c = 3 if kind == b"PF" else 1
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    if data.size != w * h * c:
        raise ImageInputError(f"{path}: PFM data hold {data.size} values, the header says {w * h * c}")
    return data.reshape(h, w, c)[::-1].astype(np.float32)


def _read_exr(path: str) -> np.ndarray:
    OpenEXR = require("OpenEXR", f"{path}: reading EXR", MissingReaderError)  # the ASWF package
    try:
        with OpenEXR.File(path) as f:
            ch = f.channels()
            if "RGB" in ch:
                return np.asarray(ch["RGB"].pixels)
            if "RGBA" in ch:
                return np.asarray(ch["RGBA"].pixels)[..., :3]
            for name in ("Y", "L", "R"):
                if name in ch:
                    return np.asarray(ch[name].pixels)
            first = sorted(ch)[0]
            return np.asarray(ch[first].pixels)
    except ImageInputError:
        raise
    except Exception as e:  # OpenEXR raises plain exceptions for unreadable files
        raise ImageInputError(f"{path}: cannot read EXR: {e}") from e


def _read_npy_image(path: str) -> np.ndarray:
    return np.load(path, allow_pickle=False)


def read_image(path: str) -> np.ndarray:
    """One image as ``(H, W, C)`` float (EXR, PFM or .npy)."""
    ext = os.path.splitext(path)[1].lower()
    readers: Dict[str, Callable[[str], np.ndarray]] = {".exr": _read_exr, ".pfm": _read_pfm, ".npy": _read_npy_image}
    if ext not in readers:
        raise ImageInputError(f"{path}: unknown image format {ext!r} (use .exr, .pfm or .npy)")
    if not os.path.exists(path):
        raise ImageInputError(f"{path}: no such file")
    try:
        return _as_hwc(readers[ext](path), path)
    except ImageInputError:
        raise
    except _READ_ERRORS as e:
        raise ImageInputError(f"{path}: cannot read: {_reason(e)}") from e


def _reason(e: BaseException) -> str:
    return e.strerror if isinstance(e, OSError) and e.strerror else (str(e) or type(e).__name__)


def _load_stack_npy(path: str) -> np.ndarray:
    try:
        a = np.load(path, allow_pickle=False)
    except _READ_ERRORS as e:  # a corrupt, truncated or unreadable .npy
        raise ImageInputError(f"{path}: cannot read: {_reason(e)}") from e
    if a.ndim not in (3, 4):
        raise ImageInputError(f"{path}: a stack must be (seeds, H, W) or (seeds, H, W, C), got shape {a.shape}")
    return a


def _read_stack_npy(path: str, seed_axis: Optional[int]) -> Samples:
    a = _load_stack_npy(path)
    if seed_axis is None:
        seed_axis = _seed_axis_of(tuple(a.shape), f"the stack {path}")
    a = np.moveaxis(a, seed_axis, 0)
    if a.ndim == 3:
        a = a[..., None]
    return Samples(a, _channel_names(a.shape[-1]))


def _read_moments_npz(path: str, z) -> Summary:
    rec = np.asarray(z["moments"])
    if rec.dtype != np.uint8 or rec.ndim not in (3, 4):
        raise ImageInputError(f"{path}: 'moments' must be a uint8 array (H, W[, C], record bytes), "
                              f"got {rec.dtype} {rec.shape}")
    try:
        acc = MomentsArray.from_bytes(np.ascontiguousarray(rec).tobytes(), tuple(rec.shape[:-1]))
    except ValueError as e:
        raise ImageInputError(f"{path}: {e}") from e
    return summary_of_moments(acc)


def _read_summary_npz(path: str) -> Summary:
    with np.load(path, allow_pickle=False) as z:
        keys = set(z.files)
        if "moments" in keys:
            return _read_moments_npz(path, z)
        if "mean" not in keys or "n" not in keys or not ({"M2", "m2", "var"} & keys):
            raise ImageInputError(f"{path}: a summary .npz needs arrays 'n', 'mean' and 'M2' (or 'var'), "
                                  f"found {sorted(keys)}")
        mean = np.asarray(z["mean"], dtype=np.float64)
        if mean.ndim not in (2, 3):
            raise ImageInputError(f"{path}: 'mean' must be (H, W) or (H, W, C), got shape {mean.shape}")
        if mean.ndim == 2:
            mean = mean[..., None]
        try:
            n = np.asarray(z["n"], dtype=np.float64)
            n = np.broadcast_to(n[..., None] if n.ndim == 2 else n, mean.shape)
            if "var" in keys and not ({"M2", "m2"} & keys):
                var = np.asarray(z["var"], dtype=np.float64)
                var = var[..., None] if var.ndim == 2 else var
                m2 = np.broadcast_to(var, mean.shape) * (n - 1)
            else:
                m2 = np.asarray(z["M2"] if "M2" in keys else z["m2"], dtype=np.float64)
                m2 = np.broadcast_to(m2[..., None] if m2.ndim == 2 else m2, mean.shape)
        except ValueError as e:
            raise ImageInputError(f"{path}: the arrays' shapes do not match 'mean' {mean.shape}: {e}") from e
    return Summary(np.ascontiguousarray(n), mean, np.ascontiguousarray(m2), _channel_names(mean.shape[-1]))


# Input kinds: a reader per kind, given the side's paths.  A new kind (e.g.
# serialized per-pixel accumulators) is one function returning Samples or
# Summary, and one entry here.
_READERS: Dict[str, Callable[..., Side]] = {
    "stack": lambda paths, seed_axis, **_: _read_stack_npy(paths[0], seed_axis),
    "summary": lambda paths, seed_axis, **_: _read_summary_npz(paths[0]),
    "images": lambda paths, seed_axis, **_: _stack_images(paths),
    "exr-moment": lambda paths, seed_axis, spp=None, **_: image_exr.read_moment(paths[0], spp),
    "exr-seeds": lambda paths, seed_axis, **_: image_exr.read_seed_layers(paths[0]),
}


def _stack_images(paths: Sequence[str]) -> Samples:
    imgs = [read_image(p) for p in paths]
    for p, im in zip(paths, imgs):
        if im.shape != imgs[0].shape:
            raise ImageInputError(f"{p}: shape {im.shape} differs from {paths[0]}'s {imgs[0].shape}")
    return Samples(np.stack(imgs), _channel_names(imgs[0].shape[-1]))


def _kind_of(paths: Sequence[str]) -> str:
    if not paths:
        raise ImageInputError("no input files")
    for p in paths:
        if not os.path.exists(p):
            raise ImageInputError(f"{p}: no such file")
    ext = os.path.splitext(paths[0])[1].lower()
    if len(paths) == 1 and ext == ".npz":
        return "summary"
    if len(paths) == 1 and ext == ".npy":
        return "stack"
    if len(paths) == 1 and ext == ".exr":
        return image_exr.kind_of(paths[0])  # a renderer's moments or several seeds' layers, by channel names
    return "images"


def load_side(paths: Union[str, Sequence[str]], *, seed_axis: Optional[int] = None,
              spp: Optional[int] = None) -> Side:
    """Reads one side of a comparison (see the module's doc for the inputs);
    `spp`: the samples per pixel of a Mitsuba moment EXR."""
    if isinstance(paths, (str, os.PathLike)):
        paths = [os.fspath(paths)]
    paths = [os.fspath(p) for p in paths]
    kind = _kind_of(paths)
    try:
        return _READERS[kind](paths, seed_axis, spp=spp)
    except ImageInputError:
        raise
    except _READ_ERRORS as e:  # a corrupt .npy / .npz (the image files' readers name their file)
        raise ImageInputError(f"{paths[0]}: cannot read: {_reason(e)}") from e


def compare(reference, candidate, *, seed_axis: Optional[int] = None, spp=None, **kw) -> ImageComparison:
    """``mcstat.image.compare`` whose sides may also be file paths
    (`load_side`); `spp`: the samples per pixel of moment EXRs, one value
    for both sides or (reference, candidate)."""
    t0 = time.perf_counter()
    spp_r, spp_c = image_exr.spp_pair(spp)
    ref, cand = _load(reference, seed_axis, spp_r), _load(candidate, seed_axis, spp_c)
    t_load = time.perf_counter() - t0
    res = _compare(ref, cand, seed_axis=seed_axis, **kw)
    res.timings["load_and_channels"] += t_load
    return res


def _load(x, seed_axis: Optional[int], spp: Optional[int] = None):
    if isinstance(x, (str, os.PathLike)) or (isinstance(x, (list, tuple)) and
                                             all(isinstance(p, (str, os.PathLike)) for p in x)):
        paths = [os.fspath(x)] if isinstance(x, (str, os.PathLike)) else [os.fspath(p) for p in x]
        if seed_axis is None and _kind_of(paths) == "stack":
            # the array as it is: the comparison settles its seeds axis
            # with the other side's shape in view
            return _load_stack_npy(paths[0])
        return load_side(paths, seed_axis=seed_axis, spp=spp)
    return x


# ---- the significance map ------------------------------------------------------
def map_rgb(res: ImageComparison) -> np.ndarray:
    """The significance map as (H, W, 3) uint8 (see COLOR_KEY)."""
    lum = res.reference_luminance
    finite = np.isfinite(lum)
    scale = np.percentile(lum[finite], 99) if finite.any() else 1.0
    scale = scale if scale > 0 else 1.0
    tm = np.where(finite, np.clip(lum, 0, None) / scale, 0.0)
    tm = tm / (1.0 + tm)  # Reinhard
    grey = (60 + 140 * tm).astype(np.uint8)
    out = np.repeat(grey[..., None], 3, axis=2)
    pd = res.pixel_decision()
    out[pd == -2] = COLOR_KEY["not tested"]
    out[pd == 1] = COLOR_KEY["greater"]
    out[pd == -1] = COLOR_KEY["less"]
    out[pd == 2] = COLOR_KEY["mixed"]
    return out


def write_map(res: ImageComparison, path: str) -> None:
    """Writes the significance map as PNG (Pillow)."""
    Image = require("PIL.Image", "writing the significance map (--png)")
    try:
        Image.fromarray(map_rgb(res), mode="RGB").save(path, format="PNG", compress_level=1)
    except OSError as e:
        raise OutputError(f"{path}: cannot write the significance map: {_reason(e)}") from e


def run(reference, candidate, *, png: Optional[str] = None, json_path: Optional[str] = None, worst: int = 10,
        **kw) -> ImageComparison:
    """`compare`, then the PNG and the JSON summary when paths are given."""
    if png:  # before the work: a missing Pillow is said at once
        require("PIL.Image", "writing the significance map (--png)")
    res = compare(reference, candidate, **kw)
    t = time.perf_counter()
    if png:
        write_map(res, png)
    res.timings["png"] = time.perf_counter() - t
    if json_path:
        try:
            with open(json_path, "w") as f:
                json.dump(res.summary(worst), f, indent=1)
        except OSError as e:
            raise OutputError(f"{json_path}: cannot write the summary: {_reason(e)}") from e
    return res
