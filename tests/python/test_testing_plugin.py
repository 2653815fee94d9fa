"""The pytest plugin (mcstat.testing.pytest_plugin) as a suite uses it: a
small suite run in a subprocess pytest, inert without the option, the
shares, the seeds, the summary, the artifacts and the refusals."""
import json
import os
import subprocess
import sys
import textwrap

import pytest

from mcstat import testing as mt

SUITE = textwrap.dedent('''
    import json, os
    import numpy as np, pytest
    from mcstat.testing import assert_unbiased, current_scope

    def ok(n, seed):
        return np.random.default_rng(seed).normal(0.0, 1.0, n)

    def biased(n, seed):
        return np.random.default_rng(seed).normal(0.2, 1.0, n)

    def log():
        sc = current_scope()
        with open(os.environ["SUITE_LOG"], "a") as f:
            f.write(json.dumps({"test": sc.name, "alpha": sc.alpha, "checks": sc.checks}) + "\\n")

    @pytest.mark.mcstat
    @pytest.mark.parametrize("k", range(3))
    def test_ok(k):
        log()
        assert_unbiased(ok, 0.0, n=2000)

    @pytest.mark.mcstat(weight=2, checks=2)
    def test_two():
        log()
        assert_unbiased(ok, 0.0, n=2000)
        assert_unbiased(ok, 0.0, n=2000)

    def test_fixture(mcstat):
        log()
        assert mcstat is not None and mcstat.checks == 1
        assert_unbiased(ok, 0.0, n=2000)

    @pytest.mark.mcstat
    def test_bias():
        log()
        assert_unbiased(biased, 0.0, n=2000)

    @pytest.mark.mcstat
    def test_overspend():
        assert_unbiased(ok, 0.0, n=2000)
        assert_unbiased(ok, 0.0, n=2000)

    def test_unmarked():
        assert_unbiased(ok, 0.0, n=2000)

    def test_plain():
        assert True
''')


def run(tmp_path, *args):
    (tmp_path / "test_suite.py").write_text(SUITE)
    logf = tmp_path / "log.jsonl"
    if logf.exists():
        logf.unlink()
    env = dict(os.environ, SUITE_LOG=str(logf))
    r = subprocess.run([sys.executable, "-m", "pytest", "-p", "no:cacheprovider", "-rA", *args],
                       cwd=tmp_path, env=env, capture_output=True, text=True, timeout=300)
    logged = [json.loads(line) for line in logf.read_text().splitlines()] if logf.exists() else []
    return r, logged


def test_inert_without_the_option(tmp_path):
    r, logged = run(tmp_path, "-k", "plain or unmarked")
    assert "1 passed" in r.stdout and "1 failed" in r.stdout, r.stdout
    assert "no suite budget is active" in r.stdout  # the assertion needs alpha= then
    assert "statistical check(s)" not in r.stdout  # no summary


def test_budget_shares_seeds_summary_and_artifacts(tmp_path):
    art = tmp_path / "art"
    r, logged = run(tmp_path, "--mcstat-alpha", "0.006", "--mcstat-seed", "11", "--mcstat-artifacts", str(art))
    out = r.stdout
    # statistical: test_ok x3 (weight 1), test_two (2), test_fixture (1), test_bias, test_overspend: weight 8
    shares = {d["test"].split("::")[1]: d["alpha"] for d in logged}
    assert shares["test_ok[0]"] == pytest.approx(0.006 / 8, rel=1e-12)
    assert shares["test_two"] == pytest.approx(0.006 * 2 / 8, rel=1e-12)
    assert shares["test_fixture"] == pytest.approx(0.006 / 8, rel=1e-12)
    # the biased test fails with its seed and how to reproduce it; the overspending one with BudgetError
    assert "FAILED test_suite.py::test_bias" in out
    seed = mt.check_seed(11, "test_suite.py::test_bias", 0)
    assert f"seed {seed}" in out
    assert "reproduce: pytest 'test_suite.py::test_bias' --mcstat-alpha 0.006 --mcstat-seed 11" in out
    assert "FAILED test_suite.py::test_overspend" in out and "one more than the 1 the test declared" in out
    assert "FAILED test_suite.py::test_unmarked" in out and "mark it @pytest.mark.mcstat" in out
    assert "3 failed, 6 passed" in out  # passed: test_ok x3, test_two, test_fixture, test_plain
    assert "mcstat: " in out and "of the suite's 0.006" in out
    # each test's share in its report section
    assert "share of the suite's alpha: 0.0015 over 2 check(s), 2 ran" in out
    # artifacts: the failed check's report
    files = sorted(p.name for p in (art / "test_suite.py_test_bias").iterdir())
    assert files == ["check0-unbiased.txt"]
    assert "One Sample t-test" in (art / "test_suite.py_test_bias" / "check0-unbiased.txt").read_text()


def test_same_seed_same_outcome_other_seed_other_draws(tmp_path):
    a, _ = run(tmp_path, "--mcstat-alpha", "0.006", "--mcstat-seed", "5", "-k", "bias")
    b, _ = run(tmp_path, "--mcstat-alpha", "0.006", "--mcstat-seed", "5", "-k", "bias")
    c, _ = run(tmp_path, "--mcstat-alpha", "0.006", "--mcstat-seed", "6", "-k", "bias")

    def stage1(r):
        return [line for line in r.stdout.splitlines() if "stage 1: n 2000" in line][0]
    assert stage1(a) == stage1(b) != stage1(c)


def test_deselection_reallocates_before_running(tmp_path):
    r, logged = run(tmp_path, "--mcstat-alpha", "0.001", "-k", "test_ok")
    assert [d["alpha"] for d in logged] == [pytest.approx(0.001 / 3, rel=1e-12)] * 3
    assert "3 passed" in r.stdout


@pytest.mark.parametrize("args, what", [(["--mcstat-alpha", "2"], "alpha must be in (0, 1)"),
                                        (["--mcstat-alpha", "0.01", "--mcstat-escalate", "0.5"], "escalate")])
def test_bad_options_are_usage_errors(tmp_path, args, what):
    r, _ = run(tmp_path, *args)
    assert r.returncode == 4 and what in r.stderr, (r.returncode, r.stderr)
