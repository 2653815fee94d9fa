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

    ref = rng.normal(size=(4, 3, 5))
    cand = rng.normal(size=(4, 3, 5)) + 0.5
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
