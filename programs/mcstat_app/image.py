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
from typing import Callable, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from mcstat import MomentsArray
from mcstat.image import (
    COLOR_KEY,
    ImageComparison,
    ImageInputError,
    Samples,
    Side,
    Summary,
    Owned,
    channel_names,
    seed_axis_of,
    summary_of_moments,
)
from mcstat.image import compare as _compare

from . import image_exr
from .errors import MissingPackageError, OutputError, require

__all__ = ["load_side", "read_image", "compare", "map_rgb", "write_map", "run", "ImageInputError",
           "MissingReaderError", "legend_rgb", "bias_map_rgb", "bias_legend_rgb", "write_bias_map"]


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


def exr_layers(names: Sequence[str]) -> Dict[str, List[str]]:
    """The colour layers of an EXR's channel names: layer -> its channels
    (R, G, B[, A] or Y), "" for the unprefixed ones (``R``, ``G``, ``B``)."""
    layers: Dict[str, List[str]] = {}
    for n in names:
        layer, _, comp = n.rpartition(".")
        layers.setdefault(layer, []).append(comp)
    return {k: v for k, v in layers.items() if {"R", "G", "B"} <= set(v) or "Y" in v}


def choose_exr_layer(path: str, names: Sequence[str], layer: Optional[str] = None) -> str:
    """The layer a comparison reads, by rule: the one asked for; else the
    unprefixed R, G, B (Mitsuba's and most renderers' beauty pass); else
    the one layer named ``Combined`` (Blender's ``ViewLayer.Combined``);
    else the only colour layer.  Anything else is ambiguous: refused,
    naming the layers the file holds."""
    layers = exr_layers(names)
    if layer is not None:
        if layer not in layers:
            raise ImageInputError(f"{path}: no colour layer {layer!r}; it holds {_layer_list(layers)}")
        return layer
    if "" in layers:
        return ""
    combined = [k for k in layers if k.rpartition(".")[2] == "Combined"]
    if len(combined) == 1:
        return combined[0]
    if len(layers) == 1:
        return next(iter(layers))
    why = "several Combined layers (view layers)" if combined else "no unprefixed R, G, B and no Combined layer"
    raise ImageInputError(f"{path}: which layer holds the render is ambiguous ({why}); it holds "
                          f"{_layer_list(layers)}: choose one with --layer NAME (layer=NAME)")


def _layer_list(layers: Dict[str, List[str]]) -> str:
    return ", ".join(repr(k) if k else "the unprefixed R, G, B" for k in sorted(layers)) or "no colour layer"


def _read_exr(path: str, layer: Optional[str] = None) -> Tuple[np.ndarray, str]:
    """One EXR image as (H, W, C) and the layer read (see choose_exr_layer)."""
    OpenEXR = require("OpenEXR", f"{path}: reading EXR", MissingReaderError)  # the ASWF package
    try:
        with OpenEXR.File(path, separate_channels=True) as f:
            ch = {k: np.asarray(v.pixels) for k, v in f.channels().items()}
    except Exception as e:  # OpenEXR raises plain exceptions for unreadable files
        raise ImageInputError(f"{path}: cannot read EXR: {e}") from e
    chosen = choose_exr_layer(path, list(ch), layer)
    comps = exr_layers(list(ch))[chosen]
    prefix = chosen + "." if chosen else ""
    order = ["R", "G", "B"] if {"R", "G", "B"} <= set(comps) else ["Y"]
    return np.stack([ch[prefix + c] for c in order], axis=-1), chosen


def _read_npy_image(path: str) -> np.ndarray:
    return np.load(path, allow_pickle=False)


def read_image(path: str, layer: Optional[str] = None) -> np.ndarray:
    """One image as ``(H, W, C)`` float (EXR, PFM or .npy); `layer`: an
    EXR's layer (default: by `choose_exr_layer`'s rule)."""
    return read_image_layer(path, layer)[0]


def read_image_layer(path: str, layer: Optional[str] = None) -> Tuple[np.ndarray, Optional[str]]:
    """`read_image` and the EXR layer it read (None for other formats)."""
    ext = os.path.splitext(path)[1].lower()
    readers: Dict[str, Callable[[str], np.ndarray]] = {".pfm": _read_pfm, ".npy": _read_npy_image}
    if ext != ".exr" and ext not in readers:
        raise ImageInputError(f"{path}: unknown image format {ext!r} (use .exr, .pfm or .npy)")
    if layer is not None and ext != ".exr":
        raise ImageInputError(f"{path}: a layer ({layer!r}) is an EXR's; this is a {ext} file")
    if not os.path.exists(path):
        raise ImageInputError(f"{path}: no such file")
    try:
        if ext == ".exr":
            img, chosen = _read_exr(path, layer)
            return _as_hwc(img, path), chosen
        return _as_hwc(readers[ext](path), path), None
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
        seed_axis = seed_axis_of(tuple(a.shape), f"the stack {path}")
    a = np.moveaxis(a, seed_axis, 0)
    if a.ndim == 3:
        a = a[..., None]
    return Samples(a, channel_names(a.shape[-1]))


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
    return Summary(np.ascontiguousarray(n), mean, np.ascontiguousarray(m2), channel_names(mean.shape[-1]))


# Input kinds: a reader per kind, given the side's paths.  A new kind (e.g.
# serialized per-pixel accumulators) is one function returning Samples or
# Summary, and one entry here.
_READERS: Dict[str, Callable[..., Side]] = {
    "stack": lambda paths, seed_axis, **_: _read_stack_npy(paths[0], seed_axis),
    "summary": lambda paths, seed_axis, **_: _read_summary_npz(paths[0]),
    "images": lambda paths, seed_axis, layer=None, **_: _stack_images(paths, layer),
    "exr-moment": lambda paths, seed_axis, spp=None, **_: image_exr.read_moment(paths[0], spp),
    "exr-seeds": lambda paths, seed_axis, **_: image_exr.read_seed_layers(paths[0]),
}


def _stack_images(paths: Sequence[str], layer: Optional[str] = None) -> Samples:
    read = [read_image_layer(p, layer) for p in paths]
    imgs = [im for im, _ in read]
    for p, im in zip(paths, imgs):
        if im.shape != imgs[0].shape:
            raise ImageInputError(f"{p}: shape {im.shape} differs from {paths[0]}'s {imgs[0].shape}")
    chosen = {c for _, c in read}
    if len(chosen) > 1:
        raise ImageInputError(f"{paths[0]} and the side's other files hold different layers by the rule "
                              f"({', '.join(sorted(repr(c) for c in chosen if c is not None))}): give --layer NAME")
    source = ""
    c = next(iter(chosen))
    if c is not None:
        what = f"layer {c!r}" if c else "the unprefixed R, G, B channels"
        source = f"read {what} of {len(paths)} EXR file(s) ({os.path.basename(paths[0])}, ...)"
    return Samples(np.stack(imgs), channel_names(imgs[0].shape[-1]), source=source)


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
              spp: Optional[int] = None, layer: Optional[str] = None) -> Side:
    """Reads one side of a comparison (see the module's doc for the inputs);
    `spp`: the samples per pixel of a Mitsuba moment EXR; `layer`: the
    layer of one-image-per-seed EXRs (default: by `choose_exr_layer`'s
    rule, and the text says which)."""
    if isinstance(paths, (str, os.PathLike)):
        paths = [os.fspath(paths)]
    paths = [os.fspath(p) for p in paths]
    kind = _kind_of(paths)
    if layer is not None and kind != "images":
        raise ImageInputError(f"{paths[0]}: --layer applies to one image per seed (EXR files); this input is {kind}")
    try:
        return _READERS[kind](paths, seed_axis, spp=spp, layer=layer)
    except ImageInputError:
        raise
    except _READ_ERRORS as e:  # a corrupt .npy / .npz (the image files' readers name their file)
        raise ImageInputError(f"{paths[0]}: cannot read: {_reason(e)}") from e


def compare(reference, candidate, *, seed_axis: Optional[int] = None, spp=None, layer: Optional[str] = None,
            **kw) -> ImageComparison:
    """``mcstat.image.compare`` whose sides may also be file paths
    (`load_side`); `spp`: the samples per pixel of moment EXRs, one value
    for both sides or (reference, candidate); `layer`: the EXR layer of
    one-image-per-seed files (default: by rule; the notes say which)."""
    t0 = time.perf_counter()
    spp_r, spp_c = image_exr.spp_pair(spp)
    # what this function loaded is handed over, not kept here (compare drops
    # it once tested); the caller's own arrays are passed as they are
    sides = _load(reference, seed_axis, spp_r, layer), _load(candidate, seed_axis, spp_c, layer)
    t_load = time.perf_counter() - t0
    res = _compare(*sides, seed_axis=seed_axis, **kw)
    res.timings["load_and_channels"] += t_load
    return res


def _load(x, seed_axis: Optional[int], spp: Optional[int] = None, layer: Optional[str] = None):
    """A side given by file paths, loaded and handed over (`Owned`); any
    other side as it is."""
    if isinstance(x, (str, os.PathLike)) or (isinstance(x, (list, tuple)) and
                                             all(isinstance(p, (str, os.PathLike)) for p in x)):
        paths = [os.fspath(x)] if isinstance(x, (str, os.PathLike)) else [os.fspath(p) for p in x]
        if seed_axis is None and _kind_of(paths) == "stack":
            # the array as it is: the comparison settles its seeds axis
            # with the other side's shape in view
            return Owned(_load_stack_npy(paths[0]))
        return Owned(load_side(paths, seed_axis=seed_axis, spp=spp, layer=layer))
    return x


# ---- the significance map ------------------------------------------------------
def _upper_quantile(v: np.ndarray, q: float) -> float:
    """The q-quantile of v by selection (np.partition, no full sort): the
    value of rank floor(q (n - 1))."""
    k = int(q * (v.size - 1))
    return float(np.partition(v, k)[k])


def _tone_scale(lum: np.ndarray) -> float:
    """The luminance s of the grey background's tone map L/s / (1 + L/s):
    the reference luminance's 99th percentile (s maps to mid grey 130)."""
    finite = lum.ravel() if np.isfinite(lum).all() else lum[np.isfinite(lum)]
    s = _upper_quantile(finite, 0.99) if finite.size else 1.0
    return s if s > 0 else 1.0


def _full_res(res: ImageComparison, a: np.ndarray) -> np.ndarray:
    """A block-resolution (H/N, W/N, ...) array upscaled to the image (H, W, ...)."""
    if res.block is None:
        return a
    h, w = res.reference_luminance.shape[:2]
    n = res.block
    return np.repeat(np.repeat(a, n, axis=0), n, axis=1)[:h, :w]


# The significance map's palette: index i is grey (i, i, i), but for the key
# colours at 1..3 (the map's greys are 60..200, the legend's 24..235, so
# greys 1..3 never occur); black, "not tested", is index 0.
_IDX = {"not tested": 0, "greater": 1, "less": 2, "mixed": 3}
_PALETTE = np.repeat(np.arange(256, dtype=np.uint8)[:, None], 3, axis=1)
for _k, _i in _IDX.items():
    _PALETTE[_i] = COLOR_KEY[_k]


def _map_index(res: ImageComparison) -> np.ndarray:
    """The significance map as (H, W) uint8 indices into `_PALETTE`."""
    lum = res.reference_luminance
    scale = _tone_scale(lum)
    # float32 and in place: at 4K each full-size temporary costs more than its arithmetic
    tm = np.nan_to_num(lum.astype(np.float32), nan=0.0, posinf=0.0, neginf=0.0)
    np.maximum(tm, 0.0, out=tm)
    tm *= np.float32(1.0 / scale)
    tm /= tm + np.float32(1.0)  # Reinhard
    tm *= np.float32(140.0)
    tm += np.float32(60.0)
    out = tm.astype(np.uint8)
    pd = _full_res(res, res.pixel_decision())
    sig = pd != 0
    if sig.any():
        lut = np.array([_IDX["not tested"], _IDX["less"], 0, _IDX["greater"], _IDX["mixed"]], dtype=np.uint8)
        out[sig] = lut[pd[sig] + 2]   # pd + 2: not tested, less, -, greater, mixed
    return out


def map_rgb(res: ImageComparison) -> np.ndarray:
    """The significance map as (H, W, 3) uint8 (see COLOR_KEY); block
    results are drawn at the image's size, each block one colour."""
    return _PALETTE[_map_index(res)]


_BAND_BG = (24, 24, 24)
_BAND_FG = (235, 235, 235)
_LEGEND_W = 600   # the legend's width at scale 1 (Pillow's built-in bitmap font, ~6 px a character)
_ROW = 14


def _legend_scale(w: int) -> int:
    # a legend readable beside a 4K image: drawn at 1x, enlarged by whole pixels
    return max(1, w // 1200)


def _compose(img: np.ndarray, legend: np.ndarray) -> np.ndarray:
    """img on top, the legend band below; the canvas as wide as the wider."""
    h, w = img.shape[:2]
    lh, lw = legend.shape[:2]
    out = np.empty((h + lh, max(w, lw), 3), dtype=np.uint8)
    out[:] = _BAND_BG
    out[:h, :w] = img
    out[h:, :lw] = legend
    return out


def _draw_band(rows: int, w_img: int, draw_rows: Callable) -> np.ndarray:
    from PIL import Image, ImageDraw

    s = _legend_scale(w_img)
    lw = max(_LEGEND_W, -(-w_img // s))
    band = Image.new("RGB", (lw, rows * _ROW + 8), _BAND_BG)
    draw_rows(ImageDraw.Draw(band), lw)
    a = np.asarray(band)
    if s > 1:
        a = np.repeat(np.repeat(a, s, axis=0), s, axis=1)
    return a


def legend_rgb(res: ImageComparison, width: int) -> np.ndarray:
    """The significance map's key (H', W', 3) uint8: a swatch and its
    meaning per colour, the grey background's scale, alpha, the adjustment
    and the rejections."""
    scale = _tone_scale(res.reference_luminance)
    m = int(res.tested.sum())
    unit = "blocks" if res.block is not None else "tests"
    rows = [
        (COLOR_KEY["greater"], "greater: the candidate significantly brighter than the reference"),
        (COLOR_KEY["less"], "less: the candidate significantly darker"),
        (COLOR_KEY["mixed"], "mixed: channels disagree (some greater, some less)"),
        ("grey", f"not significant: grey 60..200 = reference luminance L, L/s/(1+L/s), s = {scale:.4g} "
                 "(99th percentile) -> 130"),
        (COLOR_KEY["not tested"], "not tested: constant or non-finite in both inputs, too few seeds"),
        (None, f"alpha {res.alpha:g}, {res.method} ({res.alternative}): {res.rejections} of {m} {unit} rejected"
               + (f", {res.block} x {res.block} block means" if res.block is not None else "")
               + f"; verdict: {res.verdict}"),
    ]

    def draw(d, lw: int) -> None:
        for i, (col, text) in enumerate(rows):
            y = 4 + i * _ROW
            if col == "grey":
                for j, g in enumerate((60, 130, 200)):
                    d.rectangle([4 + 8 * j, y + 1, 11 + 8 * j, y + 11], fill=(g, g, g))
                x = 34
            elif col is not None:
                d.rectangle([4, y + 1, 27, y + 11], fill=tuple(col), outline=(128, 128, 128))
                x = 34
            else:
                x = 4
            d.text((x, y), text, fill=_BAND_FG)

    return _draw_band(len(rows), width, draw)


def _to_index(rgb: np.ndarray) -> np.ndarray:
    """RGB of greys and the key colours (the legend) as `_PALETTE` indices."""
    out = rgb[..., 0].copy()
    for k, i in _IDX.items():
        if i:
            out[np.all(rgb == COLOR_KEY[k], axis=-1)] = i
    return out


def write_map(res: ImageComparison, path: str) -> None:
    """Writes the significance map as PNG (Pillow), its colour key in a
    band below the image (`legend_rgb`).  A palette PNG (one byte a pixel:
    greys and the key colours), encoded in about a quarter of an RGB one's
    time; readers see the same colours (Pillow: ``.convert("RGB")``)."""
    Image = require("PIL.Image", "writing the significance map (--png)")
    idx = _map_index(res)
    h, w = idx.shape
    legend = _to_index(legend_rgb(res, w))
    full = np.full((h + legend.shape[0], max(w, legend.shape[1])), _BAND_BG[0], dtype=np.uint8)
    full[:h, :w] = idx
    full[h:, :legend.shape[1]] = legend
    try:
        im = Image.frombytes("P", (full.shape[1], full.shape[0]), full.tobytes())
        im.putpalette(_PALETTE.tobytes())
        im.save(path, format="PNG", compress_level=1)
    except OSError as e:
        raise OutputError(f"{path}: cannot write the significance map: {_reason(e)}") from e


# ---- the detectable-bias map ------------------------------------------------------
# viridis, sampled at 9 points (dark blue: small detectable bias, i.e. sensitive)
_VIRIDIS = np.array([(68, 1, 84), (71, 44, 122), (59, 81, 139), (44, 113, 142), (33, 144, 141),
                     (39, 173, 129), (92, 200, 99), (170, 220, 50), (253, 231, 37)], dtype=np.float64)


def _colormap(t: np.ndarray) -> np.ndarray:
    """t in [0, 1] -> (..., 3) uint8 of `_VIRIDIS`, linear between its points."""
    x = np.clip(t, 0.0, 1.0) * (len(_VIRIDIS) - 1)
    i = np.minimum(x.astype(np.intp), len(_VIRIDIS) - 2)
    f = (x - i)[..., None]
    return (_VIRIDIS[i] * (1 - f) + _VIRIDIS[i + 1] * f + 0.5).astype(np.uint8)


# The bias map's palette: 0 black (not tested), 1..200 the colour scale,
# 201..255 greys 24..235 for the legend's text (anti-aliased text quantised
# to 55 greys).
_NBIAS = 200
_BIAS_PAL = np.zeros((256, 3), dtype=np.uint8)
_BIAS_PAL[1:_NBIAS + 1] = _colormap(np.linspace(0.0, 1.0, _NBIAS))
_BIAS_PAL[_NBIAS + 1:] = np.round(np.linspace(24, 235, 255 - _NBIAS)).astype(np.uint8)[:, None]


def _bias_scale(v: np.ndarray) -> tuple:
    """(lo, hi, log): the colour scale from the 1st to the 99th percentile
    of the finite values, logarithmic when they span more than a factor 10."""
    fin = np.isfinite(v)
    f = v.ravel() if fin.all() else v[fin]
    if f.size == 0:
        return 0.0, 1.0, False
    k0, k1 = int(0.01 * (f.size - 1)), int(0.99 * (f.size - 1))
    part = np.partition(f, (k0, k1))   # one selection for both
    lo, hi = float(part[k0]), float(part[k1])
    if not hi > lo:
        hi = lo + (abs(lo) if lo else 1.0)
    return lo, hi, bool(lo > 0 and hi / lo > 10)


def _bias_index(res: ImageComparison, scale: Optional[tuple] = None) -> np.ndarray:
    """The bias map as (H, W) uint8 indices into `_BIAS_PAL`."""
    v = _bias_per_pixel(res)
    lo, hi, log = scale if scale is not None else _bias_scale(v)
    bad = ~np.isfinite(v)
    with np.errstate(invalid="ignore", divide="ignore"):
        if log:
            t = np.log(v, dtype=np.float32)
            t -= np.float32(np.log(lo))
            t *= np.float32((_NBIAS - 1) / np.log(hi / lo))
        else:
            t = v.astype(np.float32)
            t -= np.float32(lo)
            t *= np.float32((_NBIAS - 1) / (hi - lo))
        t[bad] = 0.0
        np.clip(t, 0.0, _NBIAS - 1, out=t)
        t += np.float32(1.5)   # 1 + rounding
    idx = t.astype(np.uint8)
    idx[bad] = 0
    return _full_res(res, idx)


def bias_map_rgb(res: ImageComparison, scale: Optional[tuple] = None) -> np.ndarray:
    """The detectable bias (the largest over channels) in false colour,
    (H, W, 3) uint8 at the image's size; black where not tested."""
    return _BIAS_PAL[_bias_index(res, scale)]


def _bias_per_pixel(res: ImageComparison) -> np.ndarray:
    """The detectable bias, the largest over channels, NaN where not tested."""
    db = res.detectable_bias
    if db is None:
        return np.full(res.shape[:2], np.nan)
    if db.shape[-1] == 1:
        return db[..., 0]
    with np.errstate(invalid="ignore"):
        v = np.max(np.where(np.isnan(db), -np.inf, db), axis=-1)
    v[~np.isfinite(v)] = np.nan
    return v


def bias_legend_rgb(res: ImageComparison, width: int, scale: Optional[tuple] = None) -> np.ndarray:
    """The bias map's colour bar with its scale and what it shows."""
    lo, hi, log = scale if scale is not None else _bias_scale(_bias_per_pixel(res))
    ticks = [lo * (hi / lo) ** f for f in (0, 0.25, 0.5, 0.75, 1)] if log else \
            [lo + (hi - lo) * f for f in (0, 0.25, 0.5, 0.75, 1)]
    unit = "block" if res.block is not None else "pixel"
    title = (f"detectable bias per {unit}: smallest |candidate - reference| found with probability "
             f"{res.detect_power:g} at the per-test level {res.level:.3g} ({res.method}, alpha {res.alpha:g})")
    title2 = (f"{'log' if log else 'linear'} scale, 1st..99th percentile; black: not tested; "
              f"largest over channels; verdict: {res.verdict}")

    def draw(d, lw: int) -> None:
        d.text((4, 4), title, fill=_BAND_FG)
        d.text((4, 4 + _ROW), title2, fill=_BAND_FG)
        x0, x1, y = 8, lw - 40, 4 + 2 * _ROW + 2
        bar = _BIAS_PAL[1 + np.round(np.linspace(0.0, _NBIAS - 1, x1 - x0)).astype(np.intp)]
        for i in range(x1 - x0):
            d.line([(x0 + i, y), (x0 + i, y + 10)], fill=tuple(int(c) for c in bar[i]))
        for f, tv in zip((0, 0.25, 0.5, 0.75, 1), ticks):
            x = int(x0 + f * (x1 - x0 - 1))
            d.line([(x, y + 10), (x, y + 13)], fill=_BAND_FG)
            d.text((max(0, x - 12), y + 14), f"{tv:.3g}", fill=_BAND_FG)

    return _draw_band(4, width, draw)


def _bias_to_index(rgb: np.ndarray) -> np.ndarray:
    """The bias legend's RGB (greys, and the colour bar's palette colours)
    as `_BIAS_PAL` indices."""
    r = rgb[..., 0].astype(np.int32)
    g, b = rgb[..., 1].astype(np.int32), rgb[..., 2].astype(np.int32)
    grey = (r == g) & (g == b)
    q = np.clip(np.round((r - 24) * (254 - _NBIAS) / 211.0), 0, 254 - _NBIAS).astype(np.int32)
    out = (_NBIAS + 1 + q).astype(np.uint8)
    if (~grey).any():
        pal = _BIAS_PAL[1:_NBIAS + 1].astype(np.int32)
        keys = (pal[:, 0] << 16) | (pal[:, 1] << 8) | pal[:, 2]
        order = np.argsort(keys)
        k = ((r << 16) | (g << 8) | b)[~grey]
        pos = np.clip(np.searchsorted(keys[order], k), 0, _NBIAS - 1)
        out[~grey] = (1 + order[pos]).astype(np.uint8)
    return out


def write_bias_map(res: ImageComparison, path: str) -> None:
    """Writes the detectable-bias map as PNG, its colour bar and scale below."""
    Image = require("PIL.Image", "writing the detectable-bias map (--bias-png)")
    scale = _bias_scale(_bias_per_pixel(res))   # one selection for the map and its bar
    idx = _bias_index(res, scale)
    h, w = idx.shape
    legend = _bias_to_index(bias_legend_rgb(res, w, scale))
    full = np.full((h + legend.shape[0], max(w, legend.shape[1])), _NBIAS + 1, dtype=np.uint8)  # grey 24
    full[:h, :w] = idx
    full[h:, :legend.shape[1]] = legend
    try:
        # a palette PNG (one byte a pixel); zlib's run-length strategy (3):
        # the noisy false colours deflate little better with the default one,
        # at a third of the speed
        im = Image.frombytes("P", (full.shape[1], full.shape[0]), full.tobytes())
        im.putpalette(_BIAS_PAL.tobytes())
        im.save(path, format="PNG", compress_level=1, compress_type=3)
    except OSError as e:
        raise OutputError(f"{path}: cannot write the detectable-bias map: {_reason(e)}") from e


def _write_summary(path: str, summary: dict) -> None:
    """The --json summary (either test's), or OutputError naming the file."""
    try:
        with open(path, "w") as f:
            json.dump(summary, f, indent=1)
    except OSError as e:
        raise OutputError(f"{path}: cannot write the summary: {_reason(e)}") from e


def run(reference, candidate, *, png: Optional[str] = None, json_path: Optional[str] = None, worst: int = 10,
        bias_png: Optional[str] = None, **kw) -> ImageComparison:
    """`compare`, then the PNGs and the JSON summary when paths are given."""
    if png or bias_png:  # before the work: a missing Pillow is said at once
        require("PIL.Image", "writing the significance map (--png)" if png else
                "writing the detectable-bias map (--bias-png)")
    res = compare(reference, candidate, **kw)
    t = time.perf_counter()
    if png:
        write_map(res, png)
    res.timings["png"] = time.perf_counter() - t
    if bias_png:
        t = time.perf_counter()
        write_bias_map(res, bias_png)
        res.timings["bias_png"] = time.perf_counter() - t
    if json_path:
        _write_summary(json_path, res.summary(worst))
    return res


def run_equivalence(reference, candidate, *, margin: float, atol: float = 0.0, block: Optional[int] = None,
                    alpha: float = 0.05, channels: str = "luminance", seed_axis: Optional[int] = None,
                    nan_policy: str = "raise", layer: Optional[str] = None, json_path: Optional[str] = None,
                    worst: int = 10):
    """``mcstat image-test --equivalence``: `mcstat.image.equivalence` on
    per-seed inputs read as `load_side` reads them (summaries and moment
    files are refused: the blocks need the seeds), the sources read (EXR
    layers) and the JSON summary.  Returns (result, the sources' lines)."""
    from mcstat.image import equivalence

    sides, sources = [], []
    for name, x in (("reference", reference), ("candidate", candidate)):
        side = load_side(x, seed_axis=seed_axis, layer=layer)
        if not isinstance(side, Samples):
            raise ImageInputError(f"{name}: --equivalence needs per-seed renders (a .npy stack or one image per "
                                  "seed), not per-pixel summaries or moments")
        sides.append(side)
        if side.source:
            sources.append(f"  {name}: {side.source}")
    res = equivalence(sides[0], sides[1], margin=margin, atol=atol, block=32 if block is None else block,
                      alpha=alpha, channels=channels, nan_policy=nan_policy)
    if json_path:
        _write_summary(json_path, res.summary(worst))
    return res, sources

