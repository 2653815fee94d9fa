"""The library (mcstat) and the application (mcstat_app) are separate
packages: importing the library never imports the application, and the
old application paths inside the library are deprecated re-exports."""
import json
import os
import re
import subprocess
import sys

import mcstat
from conftest import ROOT

LIB = os.path.join(ROOT, "bindings", "python", "mcstat")
# The library files allowed to import the application: the deprecated shims only.
SHIMS = {"cli.py", "reproduce.py", "__main__.py", "image.py"}


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


def test_library_imports_the_application_only_in_its_shims():
    for name in sorted(os.listdir(LIB)):
        if name.endswith((".py", ".pyi")) and name not in SHIMS:
            with open(os.path.join(LIB, name), encoding="utf-8") as f:
                text = f.read()
            assert not re.search(r"(?m)^\s*(from|import)\s+mcstat_app\b|import_module\(\S*mcstat_app", text), name


def test_deprecated_paths_warn_and_reexport():
    code = r"""
import warnings, json
out = {}
with warnings.catch_warnings(record=True) as w:
    warnings.simplefilter("always")
    import mcstat.cli, mcstat_app.cli
    out["cli"] = [mcstat.cli.main is mcstat_app.cli.main, any(issubclass(x.category, DeprecationWarning) for x in w)]
with warnings.catch_warnings(record=True) as w:
    warnings.simplefilter("always")
    from mcstat.reproduce.scene import load_scene
    import mcstat.reproduce, mcstat_app.reproduce.scene, mcstat_app.reproduce.run
    out["reproduce"] = [load_scene is mcstat_app.reproduce.scene.load_scene,
                        mcstat.reproduce.run is mcstat_app.reproduce.run,
                        mcstat.reproduce.PAPER_SCENE is mcstat_app.reproduce.PAPER_SCENE,
                        any(issubclass(x.category, DeprecationWarning) for x in w)]
with warnings.catch_warnings(record=True) as w:
    warnings.simplefilter("always")
    import mcstat.image, mcstat_app.image
    out["image"] = [mcstat.image.read_image is mcstat_app.image.read_image,
                    any(issubclass(x.category, DeprecationWarning) for x in w)]
print(json.dumps(out))
"""
    out = json.loads(_python(code))
    assert out == {"cli": [True, True], "reproduce": [True, True, True, True], "image": [True, True]}


def test_compare_reading_files_is_deprecated_and_unchanged(tmp_path, rng):
    import pytest
    from mcstat_app import image as app_image

    ref = rng.normal(size=(4, 6, 5))  # (seeds, H, W): clear from the shape
    cand = rng.normal(size=(4, 6, 5)) + 0.5
    np_save = __import__("numpy").save
    np_save(tmp_path / "r.npy", ref)
    np_save(tmp_path / "c.npy", cand)
    want = mcstat.image.compare(ref, cand)
    with pytest.warns(DeprecationWarning, match="mcstat_app.image"):
        old = mcstat.image.compare(str(tmp_path / "r.npy"), str(tmp_path / "c.npy"))
    new = app_image.compare(str(tmp_path / "r.npy"), str(tmp_path / "c.npy"))
    for r in (old, new):
        assert r.pvalue.tobytes() == want.pvalue.tobytes()
    with pytest.raises(mcstat.image.ImageInputError, match="got dict"):
        mcstat.image.compare({}, cand)


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
