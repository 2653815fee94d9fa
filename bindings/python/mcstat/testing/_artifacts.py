# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""Failure artifacts for CI to upload: the report's text, and pictures.

One folder per failing test under the suite's artifact folder (its node id
made a file name), holding ``check<j>-<kind>.txt`` and, where the check has
one, ``check<j>-<kind>-<what>.png``: a map of the per-block p-values of an
image check, a histogram of both samples of a distribution check.  PNGs are
written with the standard library alone (8-bit RGB, zlib), so the package
needs no imaging dependency.
"""
from __future__ import annotations

import os
import re
import struct
import zlib
from typing import Dict, Optional, Sequence

import numpy as np

__all__ = ["png_bytes", "histogram_png", "pvalue_map_png", "write"]


def png_bytes(rgb: np.ndarray) -> bytes:
    """An 8-bit RGB image (H, W, 3) as PNG bytes."""
    a = np.ascontiguousarray(rgb, dtype=np.uint8)
    if a.ndim != 3 or a.shape[2] != 3 or a.shape[0] < 1 or a.shape[1] < 1:
        raise ValueError(f"an RGB image (H, W, 3) is needed, got shape {a.shape}")
    h, w, _ = a.shape
    raw = b"".join(b"\x00" + a[y].tobytes() for y in range(h))  # filter 0 on every row

    def chunk(tag: bytes, data: bytes) -> bytes:
        return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF)

    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw, 6)) + chunk(b"IEND", b""))


def histogram_png(a: np.ndarray, b: np.ndarray, *, bins: int = 64, width: int = 512, height: int = 256) -> bytes:
    """Both samples' histograms on common bins: a in orange, b in blue, overlap dark."""
    a = np.asarray(a, dtype=np.float64).ravel()
    b = np.asarray(b, dtype=np.float64).ravel()
    both = np.concatenate([a[np.isfinite(a)], b[np.isfinite(b)]])
    lo, hi = (float(np.min(both)), float(np.max(both))) if both.size else (0.0, 1.0)
    if not hi > lo:
        hi = lo + 1.0
    edges = np.linspace(lo, hi, bins + 1)
    ha = np.histogram(a, edges)[0] / max(a.size, 1)
    hb = np.histogram(b, edges)[0] / max(b.size, 1)
    top = max(float(ha.max(initial=0.0)), float(hb.max(initial=0.0)), 1e-300)
    img = np.full((height, width, 3), 255, np.uint8)
    col = np.minimum((np.arange(width) * bins) // width, bins - 1)
    rows = np.arange(height)[::-1][:, None]  # row index from the bottom
    in_a = rows < (ha[col] / top * (height - 1))[None, :]
    in_b = rows < (hb[col] / top * (height - 1))[None, :]
    img[in_a & ~in_b] = (240, 150, 40)
    img[in_b & ~in_a] = (60, 110, 220)
    img[in_a & in_b] = (70, 60, 90)
    return png_bytes(img)


def pvalue_map_png(p: np.ndarray, alpha: float, *, scale: int = 8) -> bytes:
    """A map of p-values (H, W) or (H, W, C) (the largest over channels):
    green where p <= alpha (shown), red shades above (darker: further from
    it), black NaN; each value a scale x scale square."""
    p = np.asarray(p, dtype=np.float64)
    if p.ndim == 3:
        p = np.where(np.isnan(p).all(axis=2), np.nan, np.nanmax(np.where(np.isnan(p), -np.inf, p), axis=2))
    img = np.zeros(p.shape + (3,), np.uint8)
    with np.errstate(invalid="ignore", divide="ignore"):
        ok = p <= alpha
        far = np.clip(np.log10(np.maximum(p, alpha) / alpha) / max(-np.log10(alpha), 1e-9), 0.0, 1.0)
    img[ok] = (40, 170, 60)
    bad = ~ok & ~np.isnan(p)
    img[bad, 0] = (255 - 120 * far[bad]).astype(np.uint8)
    img[bad, 1] = 40
    img[bad, 2] = 40
    return png_bytes(np.repeat(np.repeat(img, scale, axis=0), scale, axis=1))


def _folder_name(test: str) -> str:
    s = re.sub(r"[^A-Za-z0-9._-]+", "_", test).strip("_")
    return s[:150] or "test"


def write(root: Optional[str], test: str, index: int, kind: str, text: str,
          pictures: Optional[Dict[str, bytes]] = None) -> Sequence[str]:
    """Writes the text and pictures of one failed check; the paths written."""
    if not root:
        return []
    d = os.path.join(root, _folder_name(test))
    os.makedirs(d, exist_ok=True)
    base = os.path.join(d, f"check{index}-{kind}")
    out = [base + ".txt"]
    with open(out[0], "w", encoding="utf-8") as f:
        f.write(text + "\n")
    for what, data in (pictures or {}).items():
        path = f"{base}-{what}.png"
        with open(path, "wb") as f:
            f.write(data)
        out.append(path)
    return out
