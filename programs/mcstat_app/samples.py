# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""Reading samples for ``mcstat test``: .npy files and delimited text (.csv, .tsv, .txt)."""
from __future__ import annotations

import os
from typing import List, Optional, Tuple

import numpy as np


class SampleFileError(ValueError):
    """A sample file that cannot be read as numbers; the message names the file."""


def _parse_text(path: str, text: str) -> Tuple[np.ndarray, Optional[List[str]]]:
    lines = [ln.strip() for ln in text.splitlines()]
    lines = [ln for ln in lines if ln and not ln.startswith("#")]
    if not lines:
        raise SampleFileError(f"{path}: no data")
    delim = "," if "," in lines[-1] else ("\t" if "\t" in lines[-1] else None)

    def split(ln: str) -> List[str]:
        return [c.strip().strip('"') for c in (ln.split(delim) if delim else ln.split())]

    header = None
    try:
        [float(c) for c in split(lines[0])]
    except ValueError:
        header, lines = split(lines[0]), lines[1:]
    rows = []
    for i, ln in enumerate(lines):
        cells = split(ln)
        try:
            rows.append([float(c) if c not in ("", "NA") else np.nan for c in cells])
        except ValueError as e:
            raise SampleFileError(f"{path}: line {i + 1 + (header is not None)}: not a number ({e})") from None
    widths = {len(r) for r in rows}
    if len(widths) != 1:
        raise SampleFileError(f"{path}: rows have different numbers of columns ({sorted(widths)})")
    return np.array(rows, dtype=float), header


def load_samples(path: str, column: Optional[str] = None) -> np.ndarray:
    """One sample (1-D float64) from a file; ``column`` (index or header name)
    picks a column of a table."""
    ext = os.path.splitext(path)[1].lower()
    header = None
    try:
        if ext == ".npy":
            a = np.load(path, allow_pickle=False)
            if a.dtype.kind not in "fiub":
                raise SampleFileError(f"{path}: expected numbers, got an array of dtype {a.dtype}")
            a = a.astype(float)
        elif ext in (".csv", ".tsv", ".txt", ".dat", ""):
            with open(path, encoding="utf-8") as f:
                a, header = _parse_text(path, f.read())
        else:
            raise SampleFileError(f"{path}: expected a .npy, .csv, .tsv or .txt file, got '{ext}'")
    except OSError as e:
        raise SampleFileError(f"{path}: {e.strerror}") from None
    except EOFError:  # numpy on an empty or cut .npy
        raise SampleFileError(f"{path}: empty or truncated file") from None
    except ValueError as e:
        if isinstance(e, SampleFileError):
            raise
        raise SampleFileError(f"{path}: {e}") from None
    if a.ndim == 2 and a.shape[1] == 1 and column is None:
        a = a[:, 0]
    if a.ndim == 1:
        if column not in (None, "0"):
            raise SampleFileError(f"{path}: has one column, got --column {column}")
        return np.ascontiguousarray(a)
    if a.ndim != 2:
        raise SampleFileError(f"{path}: expected a 1-D or 2-D array, got shape {a.shape}")
    if column is None:
        names = f" ({', '.join(header)})" if header else ""
        raise SampleFileError(f"{path}: has {a.shape[1]} columns{names}; choose one with --column")
    if header and column in header:
        j = header.index(column)
    else:
        try:
            j = int(column)
        except ValueError:
            raise SampleFileError(f"{path}: no column named {column!r}"
                                  + (f" (columns: {', '.join(header)})" if header else "")) from None
        if not 0 <= j < a.shape[1]:
            raise SampleFileError(f"{path}: column {j} out of range (0..{a.shape[1] - 1})")
    return np.ascontiguousarray(a[:, j])
