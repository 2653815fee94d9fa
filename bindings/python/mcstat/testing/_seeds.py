# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""The seeds of a suite's statistical checks: a pure function of the master
seed, the test's name and the check's index in the test.

The C++ glue (mcstat_testing.h) derives them the same way, so a seed a
report prints means the same draw in either:

    seed(master, name, j) = splitmix64(master XOR fnv1a64(name + "#" + str(j)))
    stage 2 of an escalated check: splitmix64(seed + 1)

with fnv1a64 the standard 64-bit FNV-1a over the UTF-8 bytes and
splitmix64 the finalizer of Steele, Lea & Flood's SplitMix64.  Hashing the
name (not counting tests) keeps a test's seed when others are added,
removed or deselected.
"""
from __future__ import annotations

_MASK = (1 << 64) - 1


def fnv1a64(data: bytes) -> int:
    """The 64-bit FNV-1a hash of ``data``."""
    h = 0xCBF29CE484222325
    for b in data:
        h = ((h ^ b) * 0x100000001B3) & _MASK
    return h


def splitmix64(x: int) -> int:
    """SplitMix64's output for state ``x`` (one step: add the golden gamma, mix)."""
    z = (x + 0x9E3779B97F4A7C15) & _MASK
    z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & _MASK
    z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & _MASK
    return z ^ (z >> 31)


def check_seed(master: int, name: str, index: int) -> int:
    """The seed of check ``index`` (0, 1, ...) of test ``name`` under ``master``."""
    if not 0 <= master <= _MASK:
        raise ValueError(f"master seed must be in [0, 2**64), got {master}")
    return splitmix64(master ^ fnv1a64(f"{name}#{index}".encode("utf-8")))


def stage2_seed(seed: int) -> int:
    """The seed of an escalated check's second stage: independent of stage 1's draws."""
    return splitmix64((seed + 1) & _MASK)


def data_seed(master: int, name: str, label: str = "") -> int:
    """The seed of a test's own data (what the test draws itself, apart
    from the checks' uniforms): ``label`` names the draw, so a test with
    several gets independent seeds.  Never a check's seed (their keys end
    in a number, these in ``#data:label``); the same in mcstat_testing.h
    (``mcstat_testing::data_seed``), so a printed master seed reproduces
    the data in either language."""
    if not 0 <= master <= _MASK:
        raise ValueError(f"master seed must be in [0, 2**64), got {master}")
    return splitmix64(master ^ fnv1a64(f"{name}#data:{label}".encode("utf-8")))

