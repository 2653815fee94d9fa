# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""mcstat's renderer checks on Mitsuba 3's plugins, one line each.

Needs Mitsuba 3 (``pip install 'mcstat[mitsuba]'``)::

    import mcstat.mitsuba as mm
    r = mm.check_bsdf({"type": "roughconductor", "alpha": 0.2}, wi=(0.3, 0.1, 0.9))
    r = mm.check_bsdf({"type": "dielectric", "int_ior": 1.5}, wi)   # delta lobes derived
    r = mm.check_phase({"type": "hg", "g": 0.7}, wi)
    r = mm.check_emitter({"type": "rectangle", "emitter": {"type": "area"}}, ref=(0.1, 0.2, 1.0))
    r = mm.check_medium({"type": "homogeneous", "sigma_t": 2.0, "albedo": 0.75}, tmax=1.0)
    print(r)          # mcstat's CheckReport: r.reject, r.verdict, r.route("weight")...

Each takes a Mitsuba plugin dict (loaded with mi.load_dict) or an already
loaded object, and passes its other keyword arguments (``n``, ``seed``,
``alpha``, ``routes``...) to `mcstat.check_bsdf`, `mcstat.check_phase`,
`mcstat.check_emitter` or `mcstat.check_medium`.  The callables behind
them are public for other uses (`mcstat.testing`'s assertions, a
check of your own): `bsdf_model`, `phase_model`, `emitter_model`,
`medium_model` return a `BSDFModel`, `PhaseModel`, `EmitterModel` or
`MediumModel` with ``sample``, ``eval`` and ``pdf``.

**Variant.**  A dict is loaded in the variant already set; when none is,
`pick_variant` chooses ``llvm_ad_rgb`` when it works here (probed once in
a subprocess: an LLVM that cannot generate code for this CPU aborts the
process) and ``scalar_rgb`` otherwise; ``MCSTAT_MITSUBA_VARIANT`` or
``variant=`` choose.  ``DRJIT_LIBLLVM_PATH`` is pointed at Debian's
libLLVM 19 when it is installed and the variable unset (before Dr.Jit
loads).  A loaded object is used in the variant it was loaded in, set
for each call and restored after.  rgb and mono variants only.  In a JIT
variant each callable evaluates a whole batch in one Dr.Jit kernel; in
scalar_rgb it loops in Python (a whole check 6 to 17 times slower).

**What is checked.**  Channel ``channel`` (default 0) of Mitsuba's
spectra; uniforms rounded to float32 and clamped below 1 before Mitsuba
sees them; a sample whose weight is 0 in every channel, or whose pdf is
not positive, is a failed one (pdf 0, weight 0), as in Mitsuba's own chi2
adapters.  BSDFs: n_uniforms 3; the domain is the upper hemisphere for a
BSDF that only reflects, seen from above; a BSDF with discrete (delta)
lobes (dielectric, thindielectric, conductor, plastic, mask) gets lobes=
written from the physics (`delta_lobes`), their selection probabilities
computed from its parameters.  Phase functions: n_uniforms 3 (Mitsuba's
sample(ctx, mei, sample1, sample2)).  Emitters: sampled by direction from
``ref``; an area light is looked at without the rest of its scene.
Media: flights along a ray by delta tracking over sample_interaction,
checked against the medium's own coefficients.

**pytest.**  ``pytest_plugins = ["mcstat.mitsuba.fixtures"]`` in a
conftest.py gives the fixture ``mitsuba_variant`` (the variant set for a
test module, the previous one restored after).

Importing ``mcstat`` or ``mcstat.mitsuba`` does not import Mitsuba: it
is imported on the first call.
"""
from ._bsdf import BSDFModel, bsdf_model, check_bsdf
from ._emitter import EmitterModel, check_emitter, emitter_model
from ._env import ensure_variant, pick_variant
from ._lobes import delta_lobes
from ._medium import MediumModel, check_medium, medium_model
from ._phase import PhaseModel, check_phase, phase_model

__all__ = [
    "check_bsdf",
    "check_phase",
    "check_emitter",
    "check_medium",
    "bsdf_model",
    "phase_model",
    "emitter_model",
    "medium_model",
    "BSDFModel",
    "PhaseModel",
    "EmitterModel",
    "MediumModel",
    "delta_lobes",
    "pick_variant",
    "ensure_variant",
]
