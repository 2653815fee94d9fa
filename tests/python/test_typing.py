"""The Python examples of README.md and docs/*.md type-check (mypy --strict, pyright --strict
but for unused expressions and imports) against the installed package, and the self-contained
ones run; typing_prelude/check_overloads.py pins the result types of the
overloaded calls (assert_type) under both checkers.

Each ```python block becomes a module that starts by importing, from
typing_prelude/readme_names.pyi, the names it uses without assigning them
(the user's data the examples take as given, with their types)."""
import ast
import os
import re
import shutil
import subprocess
import sys

import numpy as np
import pytest

import mcstat

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))


def readme_blocks():
    """(document, block) for each ```python block of the README and the guides"""
    docs = os.path.join(ROOT, "docs")
    paths = ["README.md"] + sorted(os.path.join("docs", f) for f in os.listdir(docs) if f.endswith(".md"))
    out = []
    for rel in paths:
        with open(os.path.join(ROOT, rel), encoding="utf-8") as f:
            out += [(rel, b) for b in re.findall(r"^```python\n(.*?)^```", f.read(), flags=re.S | re.M)]
    return out


def test_readme_has_python_examples():
    assert len(readme_blocks()) >= 5


@pytest.fixture(scope="module")
def examples(tmp_path_factory):
    d = tmp_path_factory.mktemp("readme_examples")
    shutil.copy(os.path.join(HERE, "typing_prelude", "readme_names.pyi"), d / "readme_names.pyi")
    # and the overloads' promises (assert_type): checked, never run
    shutil.copy(os.path.join(HERE, "typing_prelude", "check_overloads.py"), d / "readme_example_overloads.py")
    prelude = ast.parse((d / "readme_names.pyi").read_text())
    given = {t.target.id for t in prelude.body if isinstance(t, ast.AnnAssign) and isinstance(t.target, ast.Name)}
    given.add("mcstat")
    for i, (_, block) in enumerate(readme_blocks(), 1):
        tree = ast.parse(block)
        stored = {n.id for n in ast.walk(tree) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Store)}
        stored |= {n.name for n in ast.walk(tree) if isinstance(n, (ast.FunctionDef, ast.ClassDef))}
        stored |= {(a.asname or a.name).split(".")[0] for n in ast.walk(tree)
                   if isinstance(n, (ast.Import, ast.ImportFrom)) for a in n.names}
        loaded = {n.id for n in ast.walk(tree) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load)}
        names = sorted((loaded - stored) & given)
        head = f"from readme_names import {', '.join(names)}\n" if names else ""
        (d / f"readme_example_{i}.py").write_text(head + block)
    return d


def _checker(module):
    try:
        __import__(module)
    except ImportError:
        pytest.skip(f"{module} is not installed (requirements-dev.txt lists it)")


def test_readme_examples_pass_mypy_strict(examples):
    _checker("mypy")
    files = sorted(str(p) for p in examples.glob("readme_example_*.py"))
    r = subprocess.run([sys.executable, "-m", "mypy", "--strict", "--no-incremental", "--cache-dir", os.devnull,
                        "--allow-redefinition", *files], cwd=examples, capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr


def test_readme_examples_pass_pyright(examples):
    _checker("pyright")
    (examples / "pyrightconfig.json").write_text(
        # strict, but for two rules a README example breaks on purpose: a line
        # that shows values (r.pvalue, r.conf_int) and `import numpy as np`
        '{"typeCheckingMode": "strict", "reportUnusedExpression": false, "reportUnusedImport": false, '
        '"pythonVersion": "%d.%d", "venvPath": "%s", "venv": "%s"}'
        % (sys.version_info[0], sys.version_info[1], os.path.dirname(sys.prefix), os.path.basename(sys.prefix)))
    files = sorted(str(p) for p in examples.glob("readme_example_*.py"))
    r = subprocess.run([sys.executable, "-m", "pyright", "--pythonpath", sys.executable, *files], cwd=examples,
                       capture_output=True, text=True)
    if r.returncode != 0 and "npm" in r.stderr and "error" in r.stderr.lower() and "readme_example" not in r.stdout:
        pytest.skip("pyright could not fetch its npm package: " + r.stderr.strip().splitlines()[-1])
    assert r.returncode == 0, r.stdout + r.stderr


def test_readme_examples_run(examples):
    """The blocks that need no image-sized data or renderer callbacks run
    on small data (the per-pixel and check_bsdf ones are type-checked only:
    they index pixel (540, 960) and call the user's BSDF)."""
    rng = np.random.default_rng(7)
    data = {
        "new": rng.normal(0.0, 1.0, 200), "trusted": rng.normal(0.0, 1.0, 200), "x": rng.normal(0.0, 0.5, 100),
        "before": rng.normal(1.0, 0.2, 50), "after": rng.normal(1.05, 0.2, 50),
        "batch": rng.normal(size=64), "primary": rng.exponential(size=4000),
        "pairs": [(rng.normal(size=40), rng.normal(size=40)) for _ in range(3)],
        "pvalues": rng.uniform(size=1000), "rejections": 61,
        "wo": np.array([0.3, 0.1, 0.948683]),
        # seeds-major float32 stacks, as a renderer writes them (8 seeds of a 4 x 5 image)
        "renders": rng.normal(1.0, 0.1, (8, 4, 5)).astype(np.float32),
        "reference_renders": rng.normal(1.0, 0.1, (8, 4, 5)).astype(np.float32),
    }
    blocks = readme_blocks()
    ran = 0
    for i, (doc, block) in enumerate(blocks, 1):
        if "check_bsdf" in block or "MomentsArray((1080, 1920))" in block:
            continue
        if "img" in block:  # block 1's per-pixel lines need a full image; run the rest of it
            block = "\n".join(line for line in block.splitlines() if "img" not in line and "b." not in line
                              and "b[" not in line)
        ns = dict(data, mcstat=mcstat)
        exec(compile(block, f"{doc} python block {i}", "exec"), ns)
        ran += 1
    assert ran >= 4
