# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""Mitsuba's import, its variant, and calls over batches of points.

Mitsuba is imported on first use, never when ``mcstat`` or
``mcstat.mitsuba`` is imported: Dr.Jit reads ``DRJIT_LIBLLVM_PATH`` when
it loads, so the variable must be set before.  LLVM 15 aborts in code
generation on some CPUs (a process abort, not an exception), so
`pick_variant` probes ``llvm_ad_rgb`` in a subprocess before this process
uses it.

Float32.  Mitsuba's single-precision variants compute in float32: the
uniforms mcstat supplies (float64 in [0, 1)) are rounded to float32 and
clamped below 1 (a float64 just below 1 rounds to 1.0f, outside Mitsuba's
[0, 1) contract); directions and values come back as float32 values widened
to float64.

`batch` calls a function written once on Mitsuba's types: in a JIT variant
once on whole arrays (one Dr.Jit kernel), in a scalar variant once per
point from Python.
"""
from __future__ import annotations

import contextlib
import os
import subprocess
import sys
from typing import Any, Callable, Iterator, List, Optional, Sequence, Tuple

import numpy as np

LLVM_VARIANT = "llvm_ad_rgb"
SCALAR_VARIANT = "scalar_rgb"
# Debian's libLLVM 19 (Dr.Jit's LLVM backend generates code with it where 15 aborts)
LIBLLVM_CANDIDATES = ("/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1", "/usr/lib/x86_64-linux-gnu/libLLVM-19.so",
                      "/usr/lib/llvm-19/lib/libLLVM.so.1", "/usr/lib/llvm-19/lib/libLLVM-19.so")
INSTALL_HINT = "pip install 'mcstat[mitsuba]'"

_PROBE = """
import mitsuba as mi, drjit as dr
mi.set_variant('%s')
b = mi.load_dict({'type': 'roughconductor'})
si = dr.zeros(mi.SurfaceInteraction3f, 16); si.wi = mi.Vector3f(0, 0, 1)
bs, w = b.sample(mi.BSDFContext(), si, dr.full(mi.Float, 0.3, 16), mi.Point2f(0.2, 0.7))
dr.eval(w); print('ok', w[0][0] > 0)
"""

_variant_choice: Optional[str] = None


def _point_libllvm() -> None:
    """DRJIT_LIBLLVM_PATH at Debian's libLLVM 19 when it is installed, the
    variable unset and Dr.Jit not yet loaded (later it would not be read)."""
    if "DRJIT_LIBLLVM_PATH" in os.environ or "drjit" in sys.modules:
        return
    for p in LIBLLVM_CANDIDATES:
        if os.path.exists(p):
            os.environ["DRJIT_LIBLLVM_PATH"] = p
            return


def modules() -> Tuple[Any, ...]:
    """(mitsuba, drjit), imported on first use; ImportError naming the extra
    when Mitsuba is not installed."""
    _point_libllvm()
    try:
        import drjit as dr
        import mitsuba as mi
    except ImportError as e:
        raise ImportError(f"mcstat.mitsuba needs Mitsuba 3 ({INSTALL_HINT}): {e}") from e
    return mi, dr


def pick_variant() -> str:
    """``llvm_ad_rgb`` when it runs here (probed once per process, in a
    subprocess: a broken LLVM aborts the process), else ``scalar_rgb``.
    The environment variable ``MCSTAT_MITSUBA_VARIANT`` overrides the
    choice."""
    global _variant_choice
    forced = os.environ.get("MCSTAT_MITSUBA_VARIANT")
    if forced:
        return forced
    mi, _ = modules()
    if _variant_choice is None:
        _variant_choice = SCALAR_VARIANT
        if LLVM_VARIANT in mi.variants():
            try:
                r = subprocess.run([sys.executable, "-c", _PROBE % LLVM_VARIANT], capture_output=True, text=True,
                                   timeout=300, env=os.environ.copy())
                if r.returncode == 0 and "ok True" in r.stdout:
                    _variant_choice = LLVM_VARIANT
            except (OSError, subprocess.SubprocessError):
                pass
    return _variant_choice


def ensure_variant(variant: Optional[str] = None) -> str:
    """Sets ``variant`` if given; otherwise keeps the variant already set,
    or sets `pick_variant`'s when none is.  Returns the variant in force."""
    mi, _ = modules()
    if variant is not None:
        if variant not in mi.variants():
            raise ValueError(f"variant: {variant!r} is not one of this Mitsuba's variants ({', '.join(mi.variants())})")
        if mi.variant() != variant:
            mi.set_variant(variant)
    elif mi.variant() is None:
        mi.set_variant(pick_variant())
    return _supported(str(mi.variant()))


def _supported(v: str) -> str:
    if "spectral" in v or "polarized" in v:
        raise ValueError(f"variant {v!r}: mcstat.mitsuba checks rgb and mono variants (a spectral variant samples "
                         "wavelengths and a polarised one returns Mueller matrices)")
    return v


def variant_of(obj: Any, base: str) -> Optional[str]:
    """The variant whose class ``base`` (``"BSDF"``, ...) ``obj`` is an
    instance of, among the variants this process has loaded; None if none."""
    mi, _ = modules()
    current = mi.variant()
    if current is not None and isinstance(obj, getattr(mi, base)):
        return str(current)
    for v in mi.variants():
        m = sys.modules.get("mitsuba." + v)
        if m is not None and isinstance(obj, getattr(m, base)):
            return str(v)
    return None


@contextlib.contextmanager
def in_variant(variant: str) -> Iterator[Any]:
    """Mitsuba with ``variant`` set for the block, the previous one restored after."""
    mi, _ = modules()
    before = mi.variant()
    if before != variant:
        mi.set_variant(variant)
    try:
        yield mi
    finally:
        if before is not None and mi.variant() != before:
            mi.set_variant(before)


def resolve(obj: Any, base: str, argname: str, variant: Optional[str]) -> Tuple[Any, str]:
    """(object, variant): ``obj`` as a loaded Mitsuba ``base`` object.  A
    dict is loaded with mi.load_dict in ``variant`` (set for the load, the
    previous one restored); without one, in the variant set, or in
    `pick_variant`'s, which stays set when none was.  An object keeps its
    own variant.  Anything else, or a dict of another kind of plugin,
    raises TypeError naming ``argname``."""
    mi, _ = modules()
    if isinstance(obj, dict):
        if "type" not in obj:
            raise TypeError(f"{argname}: a Mitsuba plugin dict needs a 'type' key, got keys {sorted(obj)}")
        if variant is None:
            v = ensure_variant(None)
        elif variant not in mi.variants():
            raise ValueError(f"variant: {variant!r} is not one of this Mitsuba's variants ({', '.join(mi.variants())})")
        else:
            v = _supported(variant)
        with in_variant(v):
            try:
                loaded = mi.load_dict(obj)
            except Exception as e:
                raise ValueError(f"{argname}: Mitsuba could not load {obj['type']!r}: {e}") from e
        mod = sys.modules["mitsuba." + v]
        if base != "Object" and not isinstance(loaded, getattr(mod, base)):  # "Object": any plugin
            raise TypeError(f"{argname}: {obj['type']!r} loads as a Mitsuba {kind(mod, loaded)}, not a {base}")
        return loaded, v
    v_obj = variant_of(obj, base)
    if v_obj is None:
        what = kind(mi, obj) if mi.variant() is not None else type(obj).__name__
        raise TypeError(f"{argname}: expected a Mitsuba {base} (a plugin dict or a loaded object), got {what}")
    if variant is not None and variant != v_obj:
        raise ValueError(f"{argname}: the object was loaded in variant {v_obj!r}, not {variant!r}")
    return obj, _supported(v_obj)


def class_name(obj: Any) -> str:
    """The plugin's C++ class (SmoothDielectric...): class_name() where
    Mitsuba has it (3.9 does), else the head of its to_string() (3.6)."""
    if hasattr(obj, "class_name"):
        return str(obj.class_name())
    return str(obj).split("[", 1)[0].strip()


def kind(mi: Any, obj: Any) -> str:
    for base in ("BSDF", "PhaseFunction", "Emitter", "Medium", "Shape", "Scene", "Texture", "Sensor", "Integrator"):
        cls = getattr(mi, base, None)
        if cls is not None and isinstance(obj, cls):
            return base
    return type(obj).__name__


def unit(v: Any, name: str) -> np.ndarray:
    """v normalised; ValueError naming ``name`` unless a finite nonzero 3-vector."""
    a = np.asarray(v, dtype=np.float64)
    if a.shape != (3,) or not np.all(np.isfinite(a)) or not np.linalg.norm(a) > 0:
        raise ValueError(f"{name}: a finite, nonzero 3-vector, not {v!r}")
    return a / np.linalg.norm(a)


def is_jit(variant: str) -> bool:
    return not variant.startswith("scalar")


def zeros(variant: str, cls: Any, width: int) -> Any:
    """A zero-initialised Mitsuba record (an interaction, a direction
    sample) of ``width`` lanes in a JIT variant, one in a scalar variant."""
    _, dr = modules()
    if is_jit(variant):
        return dr.zeros(cls, width)
    try:
        return dr.zeros(cls)
    except (TypeError, RuntimeError):  # a record Dr.Jit cannot zero in scalar mode: its default constructor
        return cls()


def constant(variant: str, cls: Any, values: Any) -> Any:
    """A vector (wi, a reference point) as a Mitsuba ``cls``: opaque in a JIT
    variant, so that Dr.Jit compiles one kernel for every wi rather than one
    per wi (a literal is baked into the kernel)."""
    _, dr = modules()
    if not is_jit(variant):
        return cls(*[float(c) for c in values])
    return cls(*[dr.opaque(dr.value_t(cls), float(c)) for c in values])


def uniforms(u: Any, variant: str) -> np.ndarray:
    """mcstat's float64 uniforms as Mitsuba takes them: float32 clamped below
    1 (float64 kept in the double variants), widened back to float64."""
    u = np.asarray(u, dtype=np.float64)
    if "double" in variant:
        out: np.ndarray = np.minimum(u, np.nextafter(1.0, 0.0))
    else:
        out = np.minimum(u.astype(np.float32), np.nextafter(np.float32(1), np.float32(0))).astype(np.float64)
    return out


def channel_of(value: Any, channel: int, what: str) -> Any:
    """Component ``channel`` of a Mitsuba spectrum (a float passes through)."""
    _, dr = modules()
    if dr.is_array_v(value) and dr.size_v(value) > 0:
        if channel >= len(value):
            raise ValueError(f"channel: {channel} is out of range: {what} has {len(value)} channel(s)")
        return value[channel]
    return value


Column = Tuple[Callable[..., Any], np.ndarray]


def batch(variant: str, fn: Callable[..., Sequence[Any]], k: int, cols: Sequence[Column],
          n_out: Optional[int] = None) -> List[np.ndarray]:
    """Calls ``fn(width, *args)`` over k points and returns its first
    ``n_out`` outputs (all by default) as float64 (or bool) NumPy arrays,
    (k,) or (k, components).  Each column is (constructor, array of k rows):
    a JIT variant gets constructor(*columns) of the whole array in one call
    (width k), a scalar variant one call per point (width 1).

    fn returns its intermediate records (interactions, samples) after the
    outputs: they stay referenced while the outputs are read.  Measured in
    llvm_ad_rgb: an emitter's pdf() whose interactions were released before
    its output was read made each check 3 times slower."""
    _, dr = modules()
    if is_jit(variant):
        args = []
        for make, a in cols:
            a = np.asarray(a)
            if a.ndim == 1:
                args.append(make(np.ascontiguousarray(a, dtype=np.float32)))
            else:
                args.append(make(*[np.ascontiguousarray(a[:, j], dtype=np.float32) for j in range(a.shape[1])]))
        outs = list(fn(k, *args))
        dr.eval(*[o for o in outs[:n_out] if dr.is_array_v(o)])  # one kernel for every output
        return [_to_numpy(dr, o, k) for o in outs[:n_out]]
    rows = []
    for i in range(k):
        args = []
        for make, a in cols:
            x = np.asarray(a[i])
            args.append(make(float(x)) if x.ndim == 0 else make(*[float(c) for c in x]))
        rows.append([_to_numpy(dr, o, 1)[0] for o in list(fn(1, *args))[:n_out]])
    if not rows:
        return []
    return [np.array([r[j] for r in rows]) for j in range(len(rows[0]))]


def _to_numpy(dr: Any, o: Any, k: int) -> np.ndarray:
    """A Mitsuba value over k points as (k,) or (k, components)."""
    if dr.is_array_v(o) and dr.size_v(o) > 0:  # a vector or spectrum: its components
        return np.stack([_to_numpy(dr, o[j], k) for j in range(len(o))], axis=1)
    # a copy in the dtype wanted, not a view of Dr.Jit's memory (holding such views
    # made every later check several times slower)
    a = np.array(o, dtype=bool if dr.is_mask_v(o) or isinstance(o, bool) else np.float64)
    out: np.ndarray = np.array(np.broadcast_to(a, (k,)))
    return out
