# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""Scene files for ``mcstat reproduce``: reading, checking, the built-in scene.

A scene (JSON or TOML) lists emitter triangles, receivers, the irradiance
estimators to compare, BRDFs with their outgoing directions, and the
parameters of each study.  Its format is ``schema.json`` (beside this file;
``mcstat schema`` prints it), checked by :mod:`.validate`, which also fills
in the defaults; this module adds the checks a schema cannot express
(degenerate triangles, zero normals, directions below the horizon, names
that must refer to something) and asks libmcest to accept the geometry and
BRDF parameters, reporting anything it refuses under the field's path.

The built-in scene (:data:`PAPER_SCENE`, also ``examples/scenes/paper.toml``)
is the paper-like scene of libmcest (``mcest_scene_paper``): a receiver at
the origin facing +z and one triangle (-0.6, -0.4, 1.0), (0.9, -0.3, 1.3),
(0.1, 0.9, 0.8) of radiance 1, area 0.995 at about unit height, tilted and
off-centre (solid angle 0.717 sr, E = 0.66454); on it the estimators' standard
deviations order as sigma_U > sigma_C > sigma_A > sigma_S.  Its two BRDFs
were chosen so that section 3.2's findings can show at the default sizes:
Ward's (rho_s 0.6, alpha 0.2 x 0.05) seen from 70 degrees, where its sampler
is far from f cos, and Ashikhmin-Shirley's (Rs 0.2, exponents 50 x 500)
seen from 30 degrees, where its sampler is close to f cos.
"""
from __future__ import annotations

import copy
import json
import math
import os
from importlib import resources
from typing import Any, Dict, List, Optional

import numpy as np

from mcstat import estimators as est
from .validate import Validator, show

__all__ = ["SceneError", "Scene", "PAPER_SCENE", "load_scene", "parse_scene", "schema", "builtin_scene"]


class SceneError(ValueError):
    """A scene file that cannot be used; ``errors`` holds one line per problem,
    each starting with the field's path (``scene.brdfs[1].alpha_x: ...``)."""

    def __init__(self, errors: List[str], source: str = "") -> None:
        self.errors = list(errors)
        self.source = source
        head = f"{source}: " if source else ""
        if len(self.errors) == 1:
            super().__init__(head + self.errors[0])
        else:
            super().__init__(head + f"{len(self.errors)} problems:\n  " + "\n  ".join(self.errors))


PAPER_SCENE: Dict[str, Any] = {
    "name": "paper",
    "description": ("The paper-like scene of section 3 (libmcest's mcest_scene_paper): a receiver at the origin "
                    "facing +z under one tilted, off-centre triangle of radiance 1 at about unit height, and two "
                    "anisotropic BRDFs, Ward's and Ashikhmin-Shirley's."),
    "emitters": [{"vertices": [[-0.6, -0.4, 1.0], [0.9, -0.3, 1.3], [0.1, 0.9, 0.8]], "radiance": 1.0}],
    "receivers": [{"name": "origin", "point": [0.0, 0.0, 0.0], "normal": [0.0, 0.0, 1.0]}],
    "estimators": ["U", "C", "A", "S"],
    "trusted": "S",
    "brdfs": [
        {"name": "ward", "model": "ward", "rho_d": 0.0, "rho_s": 0.6, "alpha_x": 0.2, "alpha_y": 0.05,
         "outgoing": {"theta": 70.0, "phi": 40.0}},
        {"name": "ashikhmin_shirley", "model": "ashikhmin_shirley", "rd": 0.0, "rs": 0.2, "n_u": 50.0,
         "n_v": 500.0, "outgoing": {"theta": 30.0, "phi": 40.0}},
    ],
    # section 3.3 is about Ward's BRDF in the paper
    "studies": {"radiance": {"brdfs": ["ward"]}},
}

_VALIDATOR: Optional[Validator] = None


def schema() -> Dict[str, Any]:
    """The scene's JSON Schema (a fresh copy)."""
    return json.loads(schema_text())


def schema_text() -> str:
    return resources.files(__package__).joinpath("schema.json").read_text(encoding="utf-8")


def _validator() -> Validator:
    global _VALIDATOR
    if _VALIDATOR is None:
        _VALIDATOR = Validator(schema())
    return _VALIDATOR


class Scene:
    """A checked scene: ``data`` (the document with every default filled in,
    JSON-ready) and the geometry as arrays.

    Attributes
    ----------
    data : dict
    source : str
        ``"built-in"`` or the file's path.
    triangles : ndarray, shape (T, 3, 3); radiances : ndarray, shape (T,)
    receivers : list of dict(name, point, normal)
    brdfs : list of dict(name, model, params, wo)  (wo a unit 3-vector)
    """

    def __init__(self, data: Dict[str, Any], source: str) -> None:
        self.data = data
        self.source = source
        self.name: str = data["name"]
        self.triangles = np.array([e["vertices"] for e in data["emitters"]], dtype=float)
        self.radiances = np.array([e["radiance"] for e in data["emitters"]], dtype=float)
        self.receivers = [dict(name=r["name"], point=np.array(r["point"], float), normal=np.array(r["normal"], float))
                          for r in data["receivers"]]
        self.estimators: List[str] = list(data["estimators"])
        self.trusted: str = data["trusted"]
        self.brdfs = [dict(name=b["name"], model=b["model"], params=_brdf_params(b), wo=outgoing_vector(b["outgoing"]))
                      for b in data["brdfs"]]
        self.studies: Dict[str, Dict[str, Any]] = data["studies"]

    @property
    def n_emitters(self) -> int:
        return len(self.triangles)

    def brdf(self, name: str) -> Dict[str, Any]:
        return next(b for b in self.brdfs if b["name"] == name)

    def make_brdf(self, name: str):
        b = self.brdf(name)
        return (est.ward if b["model"] == "ward" else est.ashikhmin_shirley)(*b["params"])


def _brdf_params(b: Dict[str, Any]) -> tuple:
    if b["model"] == "ward":
        return (b["rho_d"], b["rho_s"], b["alpha_x"], b["alpha_y"])
    return (b["rd"], b["rs"], b["n_u"], b["n_v"])


def outgoing_vector(o: Any) -> np.ndarray:
    """The unit vector of an ``outgoing`` field (a vector, or theta/phi in degrees)."""
    if isinstance(o, dict):
        t, p = math.radians(o["theta"]), math.radians(o.get("phi", 0.0))
        v = np.array([math.sin(t) * math.cos(p), math.sin(t) * math.sin(p), math.cos(t)])
    else:
        v = np.array(o, dtype=float)
    return v / np.linalg.norm(v)


def _read(path: str) -> Any:
    """The parsed document, or SceneError naming the file and the syntax error."""
    try:
        with open(path, "rb") as f:
            raw = f.read()
    except OSError as e:
        raise SceneError([f"cannot read the scene file: {e.strerror}"], path) from None
    ext = os.path.splitext(path)[1].lower()
    if ext not in (".json", ".toml"):
        raise SceneError([f"expected a .json or .toml file, got '{ext or 'no extension'}'"], path)
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as e:
        raise SceneError([f"not UTF-8 text (byte {e.start})"], path) from None
    if ext == ".json":
        try:
            return json.loads(text)
        except json.JSONDecodeError as e:
            raise SceneError([f"JSON syntax error at line {e.lineno}, column {e.colno}: {e.msg}"], path) from None
    try:
        import tomllib  # Python >= 3.11
    except ImportError:  # pragma: no cover - depends on the interpreter
        try:
            import tomli as tomllib  # type: ignore[no-redef]
        except ImportError:
            raise SceneError(["reading TOML needs Python 3.11 or later, or `pip install tomli`; "
                              "or write the scene as JSON"], path) from None
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise SceneError([f"TOML syntax error: {e}"], path) from None


def load_scene(path: Optional[str]) -> Scene:
    """The scene in ``path`` (.json or .toml), or the built-in one for None."""
    if path is None:
        return builtin_scene()
    return parse_scene(_read(path), path)


def builtin_scene() -> Scene:
    return parse_scene(copy.deepcopy(PAPER_SCENE), "built-in")


def parse_scene(doc: Any, source: str = "") -> Scene:
    """Check a parsed document and build the Scene; SceneError lists every problem."""
    data, errors = _validator().validate(doc, "scene")
    if not errors:
        errors = _semantic(doc, data)
    if errors:
        raise SceneError(errors, source)
    return Scene(data, source)


# -- what the schema cannot say ----------------------------------------------

def _semantic(raw: Dict[str, Any], d: Dict[str, Any]) -> List[str]:
    errors: List[str] = []
    bad_e, bad_r = set(), set()
    for i, e in enumerate(d["emitters"]):
        v = np.array(e["vertices"], float)
        c = np.cross(v[1] - v[0], v[2] - v[0])
        scale = np.linalg.norm(v[1] - v[0]) * np.linalg.norm(v[2] - v[0])
        if not np.linalg.norm(c) > 1e-12 * scale:
            errors.append(f"scene.emitters[{i}].vertices: expected the corners of a triangle, got "
                          f"{show(e['vertices'])}, which lie on one line (area 0)")
            bad_e.add(i)
    for i, r in enumerate(d["receivers"]):
        r.setdefault("name", f"receiver {i}")
        if not np.any(np.array(r["normal"], float)):
            errors.append(f"scene.receivers[{i}].normal: expected a non-zero vector, got {show(r['normal'])}")
            bad_r.add(i)
    names = [r["name"] for r in d["receivers"]]
    for i, n in enumerate(names):
        if names.index(n) != i:
            errors.append(f"scene.receivers[{i}].name: {n!r} is also the name of receivers[{names.index(n)}]; "
                          "expected distinct names")
    # the trusted estimator: given, or the best listed one (S, then A, C, U)
    if "trusted" in raw:
        if d["trusted"] not in d["estimators"]:
            errors.append(f"scene.trusted: expected one of the scene's estimators ({', '.join(d['estimators'])}), "
                          f"got {d['trusted']!r}")
    else:
        d["trusted"] = next(m for m in "SACU" if m in d["estimators"])
    # BRDFs: names, directions, and what libmcest accepts
    for i, b in enumerate(d["brdfs"]):
        b.setdefault("name", b["model"])
        o = b["outgoing"]
        if isinstance(o, list):
            n = math.sqrt(sum(x * x for x in o))
            if not n > 0 or o[2] / n < 1e-12:
                errors.append(f"scene.brdfs[{i}].outgoing: expected a direction above the surface (z > 0), "
                              f"got {show(o)}")
                continue
        try:
            brdf = (est.ward if b["model"] == "ward" else est.ashikhmin_shirley)(*_brdf_params(b))
            brdf.plan(outgoing_vector(o))
        except est.EstimatorError as e:
            errors.append(f"scene.brdfs[{i}]: libmcest refused these parameters: {e}")
    bnames = [b["name"] for b in d["brdfs"]]
    for i, n in enumerate(bnames):
        if bnames.index(n) != i:
            errors.append(f"scene.brdfs[{i}].name: {n!r} is also the name of brdfs[{bnames.index(n)}]; "
                          "expected distinct names (give each BRDF a name)")
    st = d["studies"]
    for study in ("sampling", "radiance", "sampler_bugs", "renderer_check"):
        listed = st[study].get("brdfs")
        if listed is None:
            st[study]["brdfs"] = list(bnames)
        else:
            for j, n in enumerate(listed):
                if n not in bnames:
                    errors.append(f"scene.studies.{study}.brdfs[{j}]: expected the name of one of the scene's "
                                  f"BRDFs ({', '.join(map(repr, bnames)) or 'it has none'}), got {n!r}")
    for field, where in (("sizes", "sampling"), ("budgets", "bugs"), ("budgets", "timing"), ("ks_n_sim", "timing"),
                         ("sizes", "sampler_bugs")):
        xs = st[where][field]
        if any(b <= a for a, b in zip(xs, xs[1:])):
            errors.append(f"scene.studies.{where}.{field}: expected increasing numbers, got {show(xs)}")
    irr = st["irradiance"]
    if irr["primary"] < irr["secondary"]:
        errors.append(f"scene.studies.irradiance.primary: expected at least `secondary` ({irr['secondary']}) "
                      f"primary estimates, so that each secondary estimate averages k >= 1 of them; "
                      f"got {irr['primary']}")
    bugs = st["bugs"]
    if bugs["budgets"][0] < bugs["secondary"]:
        errors.append(f"scene.studies.bugs.budgets[0]: expected at least `secondary` ({bugs['secondary']}) "
                      f"primary estimates, got {bugs['budgets'][0]}")
    # geometry libmcest refuses (non-finite values have been caught by the schema)
    for i, e in enumerate(d["emitters"]):
        for j, r in enumerate(d["receivers"]):
            if i in bad_e or j in bad_r:
                continue
            try:
                est.IrradiancePlan(triangle=e["vertices"], point=r["point"], normal=r["normal"],
                                   radiance=e["radiance"])
            except est.EstimatorError as ex:
                errors.append(f"scene.emitters[{i}] with scene.receivers[{j}]: libmcest refused them: {ex}")
    return errors
