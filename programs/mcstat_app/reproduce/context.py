# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""What every study shares: random streams derived from --seed, threads,
the progress bar and the text output.

Every random number of a run comes from a libmcest or K-S seed that is a
pure function of ``--seed`` and a fixed name of what it is for:
``numpy.random.SeedSequence(seed, spawn_key=(study, *indices))`` turned into
64 bits.  The key does not depend on which studies run or in which order,
so leaving a study out (or running it alone) does not change the numbers of
the others.  Within one stream libmcest's counter (``first_index``) keeps
runs and samples apart: its estimate i is a pure function of (seed, kind of
estimate, i) whatever the number of threads, and different estimators,
bugs and samplers are independent even with the same seed.  Every seed used
is recorded (``results.json``: ``seeds``).
"""
from __future__ import annotations

import sys
from typing import Any, Callable, Dict, Optional, TextIO

import numpy as np

from .studies import BY_KEY


class _NoBar:
    def __init__(self, total: float = 0, desc: str = "") -> None:
        self.n: float = 0

    def update(self, n: float = 1) -> None:
        self.n += n

    def set_postfix_str(self, s: str) -> None:
        pass

    def close(self) -> None:
        pass

    def __enter__(self) -> "_NoBar":
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()


class Context:
    """Seed streams, threads, progress bars and the stdout of one run."""

    def __init__(self, seed: int, threads: Optional[int] = None, progress: Optional[bool] = None,
                 out: Optional[TextIO] = None) -> None:
        self.seed = int(seed)
        self.threads = threads
        self.out = out if out is not None else sys.stdout
        self.seeds: Dict[str, int] = {}
        self.transcript: list = []  # everything printed, for the report
        self._progress = progress
        self._tqdm: Optional[Callable[..., Any]] = None
        if progress is not False:
            try:
                from tqdm import tqdm

                self._tqdm = tqdm
            except ImportError:
                self._tqdm = None

    def stream(self, study: str, *key: int, label: str = "") -> int:
        """A 64-bit seed for libmcest or the K-S simulation, recorded under ``label``."""
        ss = np.random.SeedSequence(self.seed, spawn_key=(BY_KEY[study].stream,) + tuple(int(k) for k in key))
        value = int(ss.generate_state(1, dtype=np.uint64)[0])
        name = label or "/".join([study] + [str(k) for k in key])
        self.seeds[name] = value
        return value

    def bar(self, total: float, desc: str):
        """A tqdm bar on stderr (shown when stderr is a terminal, or with --progress).

        `total` is the estimated work of the study (seconds of `cost`'s
        model) and each ``update(w)`` adds a step's estimate, so that the
        percentage and the time left follow the work rather than the count
        of steps (a K-S null simulated at the largest size can take most of
        a study).  The bar shows no counts: they would be model seconds."""
        if self._tqdm is None:
            return _NoBar(total, desc)
        disable = None if self._progress is None else not self._progress
        return self._tqdm(total=total, desc=desc, leave=False, disable=disable, file=sys.stderr,
                          dynamic_ncols=True, bar_format="{desc}: {percentage:3.0f}%|{bar}| [{elapsed}<{remaining}]")

    def block(self, text: str) -> None:
        """An R-style block (which ends with its own blank line)."""
        self.print(text.rstrip("\n"))

    def print(self, text: str = "") -> None:
        self.transcript.append(text)
        self.out.write(text + "\n")
        self.out.flush()

    def mark(self) -> int:
        return len(self.transcript)

    def since(self, mark: int) -> str:
        return "\n".join(self.transcript[mark:])
