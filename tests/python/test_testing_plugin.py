"""The pytest plugin (mcstat.testing.pytest_plugin) as a suite uses it: a
small suite run in a subprocess pytest, inert without the option, the
shares, the seeds, the summary, the artifacts and the refusals."""
import json
import os
import re
import subprocess
import sys
import textwrap

import numpy as np
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
    assert (f"reproduce: cd {tmp_path} && {sys.executable} -m pytest test_suite.py::test_bias --mcstat-alpha 0.006 "
            "--mcstat-seed 11 --mcstat-escalate 4 --mcstat-alpha0 0.05 --mcstat-tests 8") in out
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


def test_selection_keeps_the_suite_shares(tmp_path):
    """-k/-m deselect after the shares are fixed over the whole collection;
    a run that collects part of the suite takes the suite's count from
    --mcstat-tests; fewer than collected would overspend and is refused."""
    r, logged = run(tmp_path, "--mcstat-alpha", "0.001", "-k", "test_ok")
    assert [d["alpha"] for d in logged] == [pytest.approx(0.001 / 8, rel=1e-12)] * 3
    assert "3 passed" in r.stdout
    r, logged = run(tmp_path, "--mcstat-alpha", "0.001", "--mcstat-tests", "20", "test_suite.py::test_two")
    assert [d["alpha"] for d in logged] == [pytest.approx(0.001 * 2 / 20, rel=1e-12)]
    assert "of the suite's 20" in r.stdout
    r, _ = run(tmp_path, "--mcstat-alpha", "0.001", "--mcstat-tests", "3")
    assert r.returncode == 4 and "would spend more than the budget" in r.stderr


def test_escalate_zero_turns_escalation_off(tmp_path):
    r, _ = run(tmp_path, "--mcstat-alpha", "0.006", "--mcstat-escalate", "0", "-k", "bias")
    assert "one stage: n 2000" in r.stdout and "stage 1:" not in r.stdout, r.stdout


def test_failure_output_is_short_and_reproducible_from_anywhere(tmp_path):
    r, _ = run(tmp_path, "--mcstat-alpha", "0.006", "--mcstat-seed", "11", "-k", "bias")
    out = r.stdout
    # mcstat's own frames are hidden: the traceback ends at the test's assertion
    assert "def _decide" not in out and "__tracebackhide__" not in out
    cmd = re.search(r"reproduce: (.*?) \(the same seeds", out).group(1)
    again = subprocess.run(cmd, shell=True, cwd="/", capture_output=True, text=True, timeout=300,
                           env=dict(os.environ, SUITE_LOG=str(tmp_path / "again.jsonl")))
    assert "1 failed" in again.stdout and "test_bias" in again.stdout, again.stdout
    seed = mt.check_seed(11, "test_suite.py::test_bias", 0)
    assert f"seed {seed}" in again.stdout


def test_summary_counts_errors_before_a_decision(tmp_path):
    r, _ = run(tmp_path, "--mcstat-alpha", "0.006")
    out = r.stdout
    # test_bias fails by its check; test_overspend by BudgetError after one
    # passing check; test_unmarked by BudgetError outside the budget
    assert "failed 1 check(s), and 2 test(s) without a failing budgeted check" in out, out
    assert "FAILED test_suite.py::test_overspend (in call)" in out
    assert "FAILED test_suite.py::test_unmarked (in call)" in out


def test_under_xdist_the_controller_sees_every_check(tmp_path):
    pytest.importorskip("xdist")
    plain_report, xdist_report = tmp_path / "plain.json", tmp_path / "xdist.json"
    a, _ = run(tmp_path, "--mcstat-alpha", "0.006", "--mcstat-report", str(plain_report))
    b, _ = run(tmp_path, "--mcstat-alpha", "0.006", "--mcstat-report", str(xdist_report), "-n", "2")

    def summary(r):
        return [x for x in r.stdout.splitlines() if "statistical check(s) in" in x][0]
    assert summary(a) == summary(b) and summary(a).startswith("mcstat: 8 statistical check(s) in 7 test(s)")
    ra, rb = json.loads(plain_report.read_text()), json.loads(xdist_report.read_text())

    def key(d):
        return sorted((x["test"], x["index"], x["seed"], x["decision"], tuple(x["p_values"])) for x in d["records"])
    assert key(ra) == key(rb) and len(rb["records"]) == 8
    assert ra["failed_tests"] == rb["failed_tests"] == ["test_suite.py::test_bias", "test_suite.py::test_overspend",
                                                         "test_suite.py::test_unmarked"]


def test_exact_estimators_pass_assert_unbiased():
    with mt.scope("exact", 0.01):
        r = mt.assert_unbiased(lambda n, s: np.full(n, 0.25), 0.25, n=100)
        assert r is None
    third = np.float32(1) / np.float32(3)
    with mt.scope("exact32", 0.01):  # float32's 1/3 is 1/3 to 64 float32 ulps
        mt.assert_unbiased(lambda n, s: np.full(n, third, np.float32), 1 / 3, n=100)
    with mt.scope("exact64", 0.01), pytest.raises(mt.StatisticalAssertionError, match="an exact estimator, not"):
        mt.assert_unbiased(lambda n, s: np.full(n, float(third)), 1 / 3, n=100)
    with mt.scope("off", 0.01), pytest.raises(mt.StatisticalAssertionError, match="an exact estimator, not"):
        mt.assert_unbiased(np.full(50, 0.26), 0.25)


def test_unbiased_pass_states_the_relative_interval():
    with mt.scope("rel", 0.01) as sc:
        mt.assert_unbiased(lambda n, s: np.random.default_rng(s).normal(2.0, 0.1, n), 2.0, n=1000)
    assert "relative to 2:" in sc.records[0].could_hide


@pytest.mark.parametrize("args, what", [(["--mcstat-alpha", "2"], "alpha must be in (0, 1)"),
                                        (["--mcstat-alpha", "0.01", "--mcstat-escalate", "0.5"], "escalate")])
def test_bad_options_are_usage_errors(tmp_path, args, what):
    r, _ = run(tmp_path, *args)
    assert r.returncode == 4 and what in r.stderr, (r.returncode, r.stderr)
