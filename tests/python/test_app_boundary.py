"""The library (mcstat) and the application (mcstat_app) are separate
packages, in both directions: no library file imports the application,
the application uses only the library's public names, and the old
application paths inside the library (removed in 0.2.0) fail saying
where the name went."""
import json
import os
import re
import subprocess
import sys

import mcstat
import mcstat.image
from conftest import ROOT

LIB = os.path.join(ROOT, "bindings", "python", "mcstat")
APP = os.path.join(ROOT, "programs", "mcstat_app")


def _python(code):
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    return p.stdout


def test_import_mcstat_does_not_import_the_application():
    code = ("import sys, json, mcstat, mcstat.image, mcstat.estimators, mcstat.diagnostics; "
            "print(json.dumps(sorted(sys.modules)))")
    mods = json.loads(_python(code))
    app = [m for m in mods if m == "mcstat_app" or m.startswith("mcstat_app.")
           or m in ("mcstat.cli", "mcstat.reproduce", "mcstat._samples", "matplotlib", "tqdm", "PIL")]
    assert app == []


def _sources(top):
    for d, _, files in os.walk(top):
        for name in sorted(files):
            if name.endswith((".py", ".pyi")):
                with open(os.path.join(d, name), encoding="utf-8") as f:
                    yield os.path.relpath(os.path.join(d, name), ROOT), f.read()


def test_library_never_imports_the_application():
    files = list(_sources(LIB))
    assert any(p.endswith(os.path.join("image", "__init__.py")) for p, _ in files)
    for path, text in files:
        assert not re.search(r"(?m)^\s*(from|import)\s+mcstat_app\b|import_module\(\S*mcstat_app", text), path


def _private(name):
    return name.startswith("_") and not name.startswith("__")


def test_application_uses_only_public_library_names():
    # `from mcstat[.mod] import _x`, a private module `mcstat._mod`, `mcstat[.mod]._x`
    import ast

    files = list(_sources(APP))
    assert len(files) > 5
    bad = []
    for path, text in files:
        for node in ast.walk(ast.parse(text)):
            if isinstance(node, ast.ImportFrom) and node.level == 0 and node.module and \
                    node.module.split(".")[0] == "mcstat":
                if any(_private(p) for p in node.module.split(".")):
                    bad.append(f"{path}:{node.lineno}: from {node.module}")
                bad += [f"{path}:{node.lineno}: {node.module}.{a.name}" for a in node.names if _private(a.name)]
            elif isinstance(node, ast.Import):
                bad += [f"{path}:{node.lineno}: import {a.name}" for a in node.names
                        if a.name.split(".")[0] == "mcstat" and any(_private(p) for p in a.name.split("."))]
            elif isinstance(node, ast.Attribute) and _private(node.attr):
                base = node.value
                while isinstance(base, ast.Attribute):
                    base = base.value
                if isinstance(base, ast.Name) and base.id == "mcstat":
                    bad.append(f"{path}:{node.lineno}: mcstat....{node.attr}")
    assert bad == []


def test_removed_paths_say_where_they_went(tmp_path, rng):
    import importlib

    import numpy as np
    import pytest

    for old in ("mcstat.cli", "mcstat.reproduce", "mcstat.__main__"):
        with pytest.raises(ModuleNotFoundError):
            importlib.import_module(old)
    for name in ("load_side", "read_image", "map_rgb", "write_map", "run"):
        with pytest.raises(AttributeError, match=f"mcstat_app.image.{name}"):
            getattr(mcstat.image, name)
    np.save(tmp_path / "r.npy", rng.normal(size=(4, 6, 5)))
    with pytest.raises(mcstat.image.ImageInputError, match="mcstat_app.image.compare"):
        mcstat.image.compare(str(tmp_path / "r.npy"), str(tmp_path / "r.npy"))
    with pytest.raises(mcstat.image.ImageInputError, match="got dict"):
        mcstat.image.compare({}, rng.normal(size=(4, 6, 5)))
    # the application's own paths, which replaced them
    from mcstat_app import image as app_image
    from mcstat_app.cli import main  # noqa: F401

    ref = rng.normal(size=(4, 6, 5))  # (seeds, H, W): clear from the shape
    np.save(tmp_path / "c.npy", ref + 0.5)
    np.save(tmp_path / "r.npy", ref)
    got = app_image.compare(str(tmp_path / "r.npy"), str(tmp_path / "c.npy"))
    assert got.pvalue.tobytes() == mcstat.image.compare(ref, ref + 0.5).pvalue.tobytes()


def test_reproduce_imports_only_declared_packages(tmp_path):
    """Every third-party package a reproduce run imports is a dependency of
    mcstat or of its 'report' extra (a bare `pip install 'mcstat[report]'`
    must run `mcstat reproduce`); here the diagnostics study, which needs SciPy.
    A package that a declared one imports when it happens to be installed
    (NumPy's f2py tries charset_normalizer, which Sphinx's requests brings
    into the dev environment) is that package's business: each new top-level
    module is attributed to the module whose import statement first loaded it."""
    tomllib = __import__("pytest").importorskip("tomllib")
    with open(os.path.join(ROOT, "pyproject.toml"), "rb") as f:
        project = tomllib.load(f)["project"]
    declared = {re.split(r"[<>=!~\[; ]", r, maxsplit=1)[0].lower()
                for r in project["dependencies"] + project["optional-dependencies"]["report"]}
    scene = tmp_path / "scene.json"
    scene.write_text(json.dumps({
        "emitters": [{"vertices": [[0, 0, 1], [1, 0, 1], [0, 1, 1]]}],
        "receivers": [{"point": [0, 0, 0], "normal": [0, 0, 1]}],
        "studies": {**{k: {"enabled": False} for k in ("irradiance", "sampling", "radiance", "bugs", "timing",
                                                       "sampler_bugs")},
                    "diagnostics": {"n": 2000}}}))
    code = f"""
import builtins, io, json, os, sys, contextlib
importer = {{}}
_import = builtins.__import__
def _record(name, globals=None, locals=None, fromlist=(), level=0):
    top = name.partition(".")[0]
    if level == 0 and top not in sys.modules and top not in importer:
        importer[top] = ((globals or {{}}).get("__name__") or "").partition(".")[0]
    return _import(name, globals, locals, fromlist, level)
builtins.__import__ = _record
from mcstat_app.cli import main
with contextlib.redirect_stdout(io.StringIO()):
    rc = main(["reproduce", "--scene", {str(scene)!r}, "--no-report", "--no-progress", "--out", {str(tmp_path)!r}])
third = set()
for name, m in list(sys.modules.items()):
    f = getattr(m, "__file__", None) or ""
    if "." not in name and not name.startswith("_") and ("site-packages" in f or "dist-packages" in f):
        third.add(name)
print(json.dumps([rc, sorted(third), importer]))
"""
    rc, third, importer = json.loads(_python(code))
    assert rc == 0
    dist = {"PIL": "pillow"}

    def is_declared(m):
        return dist.get(m, m).lower() in declared

    undeclared = [m for m in third if m not in ("mcstat", "mcstat_app") and not is_declared(m)
                  and not is_declared(importer.get(m, ""))]
    assert "scipy" in third and undeclared == []
