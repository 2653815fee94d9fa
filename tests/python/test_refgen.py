"""The reference generators of tools/refgen/ and the data of tests/data/
stay in one place: every generator is registered with the driver
(tools/refgen/run.py, which runs them in dependency order), every
registered file exists, every reference file is written by a registered
generator, and the Temme coefficients special.c sums are the ones their
generator derives (exact rationals).  No generator is run here: the data
are committed, and R is not needed."""
import glob
import importlib.util
import os
import subprocess
import sys

from conftest import ROOT

REFGEN = os.path.join(ROOT, "tools", "refgen")


def load_driver():
    spec = importlib.util.spec_from_file_location("refgen_run", os.path.join(REFGEN, "run.py"))
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_every_generator_is_registered():
    run = load_driver()
    registered = {g[1][0] for g in run.GENERATORS.values()}
    scripts = {os.path.relpath(p, ROOT) for p in glob.glob(os.path.join(REFGEN, "make_*"))}
    assert scripts == registered


def test_registered_files_exist_and_data_have_a_generator():
    run = load_driver()
    written = set()
    for name, (lang, argv, ins, outs, what) in run.GENERATORS.items():
        for path in ins + outs:
            assert os.path.exists(os.path.join(ROOT, path)), (name, path)
        written.update(outs)
    data = {os.path.relpath(p, ROOT) for p in glob.glob(os.path.join(ROOT, "tests", "data", "*"))
            if os.path.isfile(p)}
    assert data - written == set(), "reference files no generator writes"


def test_dependency_order():
    run = load_driver()
    seq = run.order(run.GENERATORS)
    assert sorted(seq) == sorted(run.GENERATORS)
    pos = {n: i for i, n in enumerate(seq)}
    writer = {o: n for n, g in run.GENERATORS.items() for o in g[3]}
    for n, g in run.GENERATORS.items():
        for i in g[2]:
            if i in writer and writer[i] != n:
                assert pos[writer[i]] < pos[n], (writer[i], n)


def test_temme_coefficients_match_special_c():
    r = subprocess.run([sys.executable, os.path.join(REFGEN, "make_temme_coeffs.py"), "--check"],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "agrees, every coefficient" in r.stdout
