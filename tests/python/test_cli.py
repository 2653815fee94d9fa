"""The mcstat command: `mcstat reproduce --quick` on the default scene and on
two example scenes (no BRDF; two triangles), the qualitative outcomes the
paper reports on the default scene, reproducibility for a given seed, clear
errors for bad scenes, and the plan / scene / schema / test subcommands."""
import contextlib
import copy
import io
import json
import os
import re
import subprocess
import sys

import numpy as np
import pytest

import mcstat
from conftest import ROOT
from mcstat_app.cli import main
from mcstat_app.reproduce import PAPER_SCENE, results as R

SCENES = os.path.join(ROOT, "examples", "scenes")


def run_cli(*argv):
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            code = main(list(argv))
        except SystemExit as e:  # argparse and explicit exits
            code = e.code if isinstance(e.code, int) else 2
            err.write(str(e.code) if not isinstance(e.code, int) else "")
    return code, out.getvalue(), err.getvalue()


def strict_json(path):
    def no_nan(x):
        raise AssertionError(f"non-finite number {x} in {path}")

    with open(path, encoding="utf-8") as f:
        return json.loads(f.read(), parse_constant=no_nan)


def quick_run(tmp_path_factory, name, *extra):
    d = str(tmp_path_factory.mktemp(name))
    code, out, err = run_cli("reproduce", "--quick", "--out", d, "--no-progress", *extra)
    assert code == 0, err
    return dict(dir=d, out=out, res=strict_json(os.path.join(d, "results.json")))


@pytest.fixture(scope="module")
def paper(tmp_path_factory):
    return quick_run(tmp_path_factory, "paper")


@pytest.fixture(scope="module")
def no_brdf(tmp_path_factory):
    return quick_run(tmp_path_factory, "no_brdf", "--scene", os.path.join(SCENES, "no_brdf.json"))


@pytest.fixture(scope="module")
def two_triangles(tmp_path_factory):
    return quick_run(tmp_path_factory, "two", "--scene", os.path.join(SCENES, "two_triangles.toml"))


# -- the default scene: the paper's findings (ERRATA 10) -----------------------

def test_paper_means_agree_with_lambert(paper):
    rec = paper["res"]["studies"]["irradiance"]["receivers"][0]
    assert rec["lambert"] == pytest.approx(0.664537151664300, rel=1e-14)
    for m in "UCAS":
        s = rec["one_sample"][m]
        # false rejections at about alpha: an exact binomial test does not refute rate = alpha
        assert s["binom_pvalue"] >= 0.001, (m, s["rejections"], s["tests"])
        assert s["counts"]["equal"] + s["rejections"] == s["tests"] == 100
        assert len(s["results"]["pvalue"]) == 100


def test_paper_variance_ordering(paper):
    o = paper["res"]["studies"]["irradiance"]["receivers"][0]["ordering"]
    assert o["order"] == ["U", "C", "A", "S"] and o["text"] == "σU > σC > σA > σS"
    assert all(step["test"]["decision"] == "greater" for step in o["steps"])


def test_paper_figure4_diagonal_and_fields(paper):
    rec = paper["res"]["studies"]["irradiance"]["receivers"][0]
    m = rec["matrix"]
    for a in range(4):
        # an estimator against itself: equal in most runs, for means and variances
        assert m["mean"][a][a]["equal"] >= 80 and m["variance"][a][a]["equal"] >= 80
    # A against S: the F test says greater in (nearly) every run
    assert m["variance"][2][3]["greater"] >= 95
    cols = m["tests"]["U vs C"]["mean"]
    for f in ("statistic", "df", "pvalue", "conf_int", "estimate", "reject", "decision", "critical_values"):
        assert len(cols[f]) == 100, f
    assert cols["method"] == "Welch Two Sample t-test"


def test_paper_equivalence_and_sample_size(paper):
    """Beyond the paper: TOST against Lambert and the samples needed to see a bias."""
    rec = paper["res"]["studies"]["irradiance"]["receivers"][0]
    eq = rec["equivalence"]
    E = rec["lambert"]
    assert eq["margins"] == [0.01, 0.001] and eq["biases"] == [0.01, 0.001] and eq["power"] == 0.9
    k = paper["res"]["studies"]["irradiance"]["k"]
    for m in "UCAS":
        e = eq["estimators"][m]
        one = e["equivalence"][0]
        # the decision is the interval inside the margin (TOST's duality), and it re-runs identically
        lo, hi = one["conf_int"]
        assert one["equivalent"] == (E * (1 - 0.01) < lo and hi < E * (1 + 0.01))
        # n scales as 1/bias^2: a 10x smaller bias needs ~100x the samples
        n1, n01 = (q["n_primary"] for q in e["sample_size"])
        assert 95 < n01 / n1 < 105
        assert e["sd_primary_estimated"] == pytest.approx(rec["sd_primary_estimated"][m], rel=1e-12)
        assert e["n_primary"] == e["n_secondary"] * k
    # S (the best estimator) is shown within 1% of E in the quick budget, and needs the fewest samples
    assert eq["estimators"]["S"]["equivalence"][0]["equivalent"]
    need = {m: eq["estimators"][m]["sample_size"][1]["n_primary"] for m in "UCAS"}
    assert need["S"] < need["A"] < need["C"] < need["U"]
    report = open(os.path.join(paper["dir"], "report.md"), encoding="utf-8").read()
    assert "Is the bias small? Equivalence and sample size" in report
    assert "Equivalence with Lambert's formula (TOST" in paper["out"]


def test_paper_bugs_detected(paper):
    b = paper["res"]["studies"]["bugs"]["receivers"][0]["summary"]
    for bug in ("no_cosine", "barycentric", "no_jacobian"):
        assert b[bug]["detected"] and b[bug]["rate_at_largest"] >= 0.9, bug
    assert b["barycentric"]["direction"] == "less" and b["no_jacobian"]["direction"] == "greater"
    assert b["none"]["pooled"]["binom_pvalue"] >= 0.001  # the correct A: rejections at about alpha


def test_paper_samplers(paper):
    brdfs = {b["name"]: b for b in paper["res"]["studies"]["sampling"]["brdfs"]}
    ward = {r["n"]: r for r in brdfs["ward"]["sizes"]}
    a_s = {r["n"]: r for r in brdfs["ashikhmin_shirley"]["sizes"]}
    # Ward's sampler is rejected from a few hundred directions on
    assert all(r["rate"] >= 0.9 for n, r in ward.items() if n >= 1000)
    # Ashikhmin-Shirley's passes at small sizes and fails at large ones
    assert all(r["rate"] <= 0.2 for n, r in a_s.items() if n <= 300)
    assert a_s[10000]["verdict"] == "fails"
    # Ward is caught at a smaller size than Ashikhmin-Shirley
    first_fail = lambda rows: min(n for n, r in rows.items() if r["verdict"] == "fails")
    assert first_fail(ward) < first_fail(a_s)
    assert brdfs["ward"]["results"] if "results" in brdfs["ward"] else True
    assert len(ward[10]["results"]["pvalue"]) == 10 and ward[10]["results"]["weight"][0] == "canner"


def test_paper_sampler_bugs(paper):
    # 3.2+: every planted sampler bug caught by the chi-squared route at the largest quick size,
    # the correct samplers rejected at about alpha by both routes, chi-squared never later than K-S
    r = paper["res"]["studies"]["sampler_bugs"]
    assert r["sizes"] == [100, 300, 1000, 3000] and r["runs"] == 20 and r["alpha"] == 0.01
    assert [b["name"] for b in r["brdfs"]] == ["ward", "ashikhmin_shirley"]
    for b in r["brdfs"]:
        last = b["sizes"][-1]["variants"]
        for bug in ("roughness", "axes_swapped", "phi_half", "jacobian"):
            assert last[bug]["chisq"]["rate"] >= 0.9, (b["name"], bug)
            d = b["summary"][bug]
            assert d["chisq"]["detected_from"] is not None
            assert d["ks"]["detected_from"] is None or d["chisq"]["detected_from"] <= d["ks"]["detected_from"]
        for route in ("chisq", "ks"):
            assert b["size_check"][route]["binom_pvalue"] >= 0.001, (b["name"], route)
            assert b["size_check"][route]["tests"] == 80
        assert all(abs(c["sum_minus_one"]) < 1e-5 for c in b["cells"])
    assert any(f.startswith("3.2+ ward: planted sampler bugs") for f in paper["res"]["findings"])
    report = open(os.path.join(paper["dir"], "report.md"), encoding="utf-8").read()
    assert "## 3.2+ Planted sampler bugs" in report and "sampler_bugs_ward.png" in report
    assert "Chi-squared test for given probabilities" in paper["out"]


def test_paper_renderer_check(paper):
    # the kit on the paper's BRDFs: every planted bug caught in every quick run (fixed seeds), the correct
    # BRDFs not rejected more often than alpha allows
    r = paper["res"]["studies"]["renderer_check"]
    assert r["n"] == 20000 and r["runs"] == 5 and r["alpha"] == 0.01
    assert [b["name"] for b in r["brdfs"]] == ["ward", "ashikhmin_shirley"]
    for b in r["brdfs"]:
        rows = {row["variant"]: row for row in b["variants"]}
        assert list(rows) == ["none", "roughness", "jacobian", "pdf", "eval", "weight"]
        for bug in ("roughness", "jacobian", "pdf", "eval", "weight"):
            assert rows[bug]["rejections"] == 5, (b["name"], bug)
        assert rows["eval"]["by_route"].get("weight") == 5 and rows["pdf"]["by_route"].get("pdf_value") == 5
        assert rows["none"]["binom_pvalue"] >= 0.001
    assert any(f.startswith("kit ward: check_bsdf") for f in paper["res"]["findings"])
    report = open(os.path.join(paper["dir"], "report.md"), encoding="utf-8").read()
    assert "## The renderer's test kit on planted bugs" in report
    assert "BSDF check: do sample(), pdf(), eval() and the weights agree?" in paper["out"]


def test_paper_radiance_counts(paper):
    r = paper["res"]["studies"]["radiance"]
    b = r["brdfs"][0]
    assert b["name"] == "ward" and b["tests_ok"] == r["directions"] == 200
    assert b["counts"]["equal"] + b["rejections"] == 200
    assert b["binomial"]["x"] == b["rejections"] and b["binomial"]["p0"] == 0.01


def test_paper_diagnostics(paper):
    """Every estimator the studies test is diagnosed; none of the
    paper's has a heavy tail, the scene's k = 100 suffices for U, C, A, S,
    and the report has the section."""
    dg = paper["res"]["studies"]["diagnostics"]
    rec = dg["receivers"][0]
    assert list(rec["estimators"]) == ["U", "C", "A", "S"] and rec["k"] == 100 and rec["m"] == 50
    for m, d in rec["estimators"].items():
        assert not d["heavy_tail"] and d["study_k_ok"] and d["recommended_k"] <= 100, m
        assert d["n"] == dg["n"] == 20000 and d["batch_k"] == 100 and d["batch_m"] == 200
        assert 0 <= d["shapiro_pvalue"] <= 1 and d["skewness_se"] > 0
    assert rec["estimators"]["U"]["skewness"] > 1  # U: a few large cosines, right-skewed
    ward = dg["brdfs"][0]
    assert ward["name"] == "ward" and list(ward["estimators"]) == ["sampling", "rejection"] and ward["alpha"] == 0.01
    assert not any(d["heavy_tail"] for d in ward["estimators"].values())
    report = open(os.path.join(paper["dir"], "report.md"), encoding="utf-8").read()
    assert "## Estimator diagnostics" in report and "| rejection |" in report
    assert sum(f.startswith("Diagnostics, ") for f in paper["res"]["findings"]) == 2


def test_paper_outputs(paper):
    d, res, out = paper["dir"], paper["res"], paper["out"]
    report = open(os.path.join(d, "report.md"), encoding="utf-8").read()
    for png in re.findall(r"!\[[^]]*\]\(([^)]+)\)", report):
        assert os.path.getsize(os.path.join(d, png)) > 1000, png
    assert len(re.findall(r"\.png\)", report)) >= 9
    for f in res["findings"]:
        assert f in report and f in out
    for marker in ("One Sample t-test", "Welch Two Sample t-test", "F test to compare two variances",
                   "Kolmogorov-Smirnov test with Canner's weight", "Exact binomial test", "left out:"):
        assert marker in out, marker
    assert all(isinstance(v, int) and 0 <= v < 2 ** 64 for v in res["seeds"].values()) and len(res["seeds"]) > 10
    assert res["command"] == "mcstat reproduce --seed 1 --quick" and res["quick"] is True
    assert "timing" in res and res["timing"]["irradiance"]["estimators"]["S"]["efficiency"] > 0
    # S against every other estimator with mcstat.efficiency_test, in the summary, JSON and report
    comp = res["timing"]["irradiance"]["comparisons"]
    assert comp["reference"] == "S" and [t["y"] for t in comp["tests"]] == ["U", "C", "A"]
    for t in comp["tests"]:
        lo, hi = t["conf_int"]
        assert 0 < lo <= t["ratio"] <= hi and t["result"]["method"] == "Efficiency ratio test (delta method)"
        assert t["result"]["nobs"] == [comp["batches"] * comp["batch_size"]] * 2
        assert f"S is {t['ratio']:.3g}x as efficient as {t['y']}, 95% CI [{lo:.3g}, {hi:.3g}]" in out
    assert "| S / A |" in report and "Is the difference in efficiency real?" in report


def test_same_seed_same_results(paper, tmp_path):
    code, _, err = run_cli("reproduce", "--quick", "--out", str(tmp_path), "--no-progress", "--no-report",
                           "--threads", "1")
    assert code == 0, err
    again = strict_json(os.path.join(tmp_path, "results.json"))
    assert not os.path.exists(os.path.join(tmp_path, "report.md"))
    a, b = R.dumps(R.without_wall_clock(paper["res"])), R.dumps(R.without_wall_clock(again))
    assert a == b
    assert "wall_seconds" in paper["res"] and "wall_seconds" not in a


def test_another_seed_other_numbers(tmp_path):
    scene = copy.deepcopy(PAPER_SCENE)
    scene["studies"] = {s: {"enabled": False} for s in ("sampling", "radiance", "bugs", "timing", "sampler_bugs",
                                                            "sequential")}
    scene["studies"]["irradiance"] = {"runs": 5}
    path = tmp_path / "small.json"
    path.write_text(json.dumps(scene))
    got = []
    for seed in ("1", "2"):
        code, _, err = run_cli("reproduce", "--scene", str(path), "--seed", seed, "--out", str(tmp_path / seed),
                               "--no-report", "--no-progress")
        assert code == 0, err
        got.append(strict_json(tmp_path / seed / "results.json"))
    # without matplotlib and tqdm (None in sys.modules makes their import fail): --no-report works,
    # and a report is refused with the command that installs them
    blocked = "import sys; sys.modules['matplotlib'] = sys.modules['tqdm'] = None; from mcstat_app.cli import main; "
    for extra, status in (["--no-report"], 0), ([], 4):
        argv = ["reproduce", "--scene", str(path), "--out", str(tmp_path / f"b{status}")] + extra
        p = subprocess.run([sys.executable, "-c", blocked + f"sys.exit(main({argv!r}))"], capture_output=True, text=True)
        assert p.returncode == status, p.stderr[-500:]
    assert "pip install 'mcstat[report]'" in p.stderr and "matplotlib and tqdm" in p.stderr
    assert (tmp_path / "b0" / "results.json").exists() and not (tmp_path / "b4").exists()
    p1 = got[0]["studies"]["irradiance"]["receivers"][0]["one_sample"]["S"]["results"]["pvalue"]
    p2 = got[1]["studies"]["irradiance"]["receivers"][0]["one_sample"]["S"]["results"]["pvalue"]
    assert p1 != p2 and got[0]["seeds"] != got[1]["seeds"]


def test_report_figures_legible_in_print(paper, tmp_path, monkeypatch):
    """Every figure of the report at its printed size: within a page's text
    width, every text at least 7 pt, a colour bar beside each 2-D histogram
    (fig6); the check itself finds a small font and a missing colour bar."""
    import collections

    import matplotlib.pyplot as plt
    from mcstat_app.reproduce import plots, report

    fig, ax = plt.subplots(figsize=(plots.TEXT_WIDTH + 1, 2))
    ax.imshow(np.eye(3))
    ax.set_title("small", fontsize=5)
    problems = plots.legibility_problems(fig)
    plt.close(fig)
    assert len(problems) == 3 and "'small' at 5.0 pt" in " ".join(problems)

    seen = {}
    real_save = plots._save

    def save(fig, path):
        seen[os.path.basename(path)] = plots.legibility_problems(fig)
        real_save(fig, path)

    monkeypatch.setattr(plots, "_save", save)
    report.write(str(tmp_path), paper["res"], collections.defaultdict(str))
    assert {"fig4_origin.png", "fig5_origin.png", "fig6_ward.png", "sampler_bugs_ward.png"} <= set(seen)
    assert {name: p for name, p in seen.items() if p} == {}


# -- example scenes ------------------------------------------------------------

def test_no_brdf_scene(no_brdf):
    res, out = no_brdf["res"], no_brdf["out"]
    assert set(res["studies"]) == {"irradiance", "bugs", "sequential", "diagnostics"} and "ks" not in res["timing"]
    left = {(s["study"], s["reason"]) for s in res["plan"]["left_out"]}
    assert ("sampling", "the scene has no BRDFs") in left and ("radiance", "the scene has no BRDFs") in left
    assert ("diagnostics", "the scene has no BRDFs") in left and res["studies"]["diagnostics"]["brdfs"] == []
    assert ("sampler_bugs", "the scene has no BRDFs") in left
    report = open(os.path.join(no_brdf["dir"], "report.md"), encoding="utf-8").read()
    assert report.count("the scene has no BRDFs") == 5 and "BRDF sampling (3.2)" in report
    assert "the scene has no BRDFs" in out
    assert [r["name"] for r in res["studies"]["irradiance"]["receivers"]] == ["floor", "wall"]
    for r in res["studies"]["irradiance"]["receivers"]:
        assert all(s["binom_pvalue"] >= 0.001 for s in r["one_sample"].values())


def test_two_triangle_scene(two_triangles):
    res = two_triangles["res"]
    rec = res["studies"]["irradiance"]["receivers"][0]
    assert rec["one_sample"] is None and rec["lambert"] is None
    assert "equivalence" not in rec  # stated relative to an exact E, which this scene lacks
    assert rec["matrix"]["estimators"] == ["C", "A", "S"]  # only the listed estimators run
    assert set(rec["against_trusted"]) == {"C", "A"}
    assert all(s["binom_pvalue"] >= 0.001 for s in rec["against_trusted"].values())
    assert set(res["timing"]["irradiance"]["estimators"]) == {"C", "A", "S"}
    assert [(t["x"], t["y"]) for t in res["timing"]["irradiance"]["comparisons"]["tests"]] == [("S", "C"), ("S", "A")]
    assert res["timing"]["irradiance"]["lambert"] is None
    reasons = " ".join(s["reason"] for s in res["plan"]["left_out"])
    assert "2 emitter triangles" in reasons and "studies.radiance.enabled = false" in reasons
    assert "radiance" not in res["studies"]
    assert all(b["detected"] for k, b in res["studies"]["bugs"]["receivers"][0]["summary"].items() if k != "none")
    # the two triangles' estimates are summed: the trusted S's mean is the sum of both Lambert values
    exact = res["plan"]["receivers"][0]["exact_per_triangle"]
    h = rec["histograms"]["S"]
    assert abs(h["mean"] - sum(exact)) < 5 * h["sd"] / np.sqrt(h["n"])


# -- errors --------------------------------------------------------------------

def test_bad_scene_file(tmp_path):
    scene = copy.deepcopy(PAPER_SCENE)
    scene["brdfs"][0]["alpha_x"] = -2
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(scene))
    out_dir = tmp_path / "out"
    code, out, err = run_cli("reproduce", "--scene", str(path), "--out", str(out_dir))
    assert code == 3 and not out_dir.exists()
    assert f"bad scene: {path}: scene.brdfs[0].alpha_x: expected a number >= 0.0001 and <= 10, got -2" in err
    code, _, err = run_cli("plan", str(tmp_path / "nope.toml"))
    assert code == 3 and "cannot read the scene file" in err


def test_missing_report_packages(monkeypatch, tmp_path):
    import mcstat_app.reproduce.run as run_mod

    monkeypatch.setattr(run_mod, "missing_report_packages", lambda: ["matplotlib"])
    code, _, err = run_cli("reproduce", "--out", str(tmp_path / "o"))
    assert code == 4 and "pip install 'mcstat[report]'" in err and "matplotlib" in err
    assert not (tmp_path / "o").exists()


# -- the other subcommands -----------------------------------------------------

def test_plan_scene_schema():
    code, out, _ = run_cli("plan", os.path.join(SCENES, "minimal.json"))
    assert code == 0 and "[3.2] all: BRDF sampling (3.2): the scene has no BRDFs" in out
    code, out, _ = run_cli("scene")
    assert code == 0 and json.loads(out)["studies"]["sampling"]["runs"] == 100
    code, out, _ = run_cli("schema")
    assert code == 0 and json.loads(out)["title"] == "mcstat reproduce: scene"
    code, _, _ = run_cli()
    assert code == 2


def test_test_subcommand(tmp_path):
    rng = np.random.default_rng(4)
    x, y = rng.normal(1.0, 1.0, 200), rng.normal(1.3, 1.0, 200)
    np.save(tmp_path / "x.npy", x)
    with open(tmp_path / "t.csv", "w") as f:
        f.write("new,trusted\n" + "".join(f"{float(a)!r},{float(b)!r}\n" for a, b in zip(x, y)))
    np.savetxt(tmp_path / "y.txt", y)
    code, out, _ = run_cli("test", str(tmp_path / "x.npy"), str(tmp_path / "y.txt"))
    assert code == 0 and out == mcstat.t_test(x, y).format("x.npy", "y.txt")
    code, out, _ = run_cli("test", str(tmp_path / "t.csv"), "--column", "trusted", "--mu", "1.3", "--alpha", "0.01")
    assert code == 0 and out == mcstat.t_test(y, mu=1.3, alpha=0.01).format("t.csv", "y")
    code, out, _ = run_cli("test", str(tmp_path / "x.npy"), "--test", "var", "--sigma2", "1", "--batch", "4")
    assert out == mcstat.var_test(mcstat.batch_means(x, 4), sigma2=1.0).format("x.npy", "y")
    code, out, _ = run_cli("test", str(tmp_path / "x.npy"), str(tmp_path / "y.txt"), "--test", "ks", "--json")
    fields = json.loads(out)
    ks = mcstat.ks_test(x, y)
    assert fields["pvalue"] == ks.pvalue and fields["weight"] == "canner"
    code, _, _ = run_cli("test", str(tmp_path / "x.npy"), str(tmp_path / "y.txt"), "--fail-on-reject",
                         "--alpha", "0.5")
    assert code == (1 if mcstat.t_test(x, y, alpha=0.5).reject else 0)
    # errors say what to do
    code, _, err = run_cli("test", str(tmp_path / "t.csv"))
    assert code == 3 and "has 2 columns (new, trusted); choose one with --column" in err
    code, _, err = run_cli("test", str(tmp_path / "x.npy"), "--test", "var")
    assert code == 2 and "needs --sigma2" in err
    (tmp_path / "bad.csv").write_text("1.0\nabc\n")
    code, _, err = run_cli("test", str(tmp_path / "bad.csv"))
    assert code == 3 and "bad.csv: line 2: not a number" in err
    np.save(tmp_path / "c.npy", np.ones(10))
    code, _, err = run_cli("test", str(tmp_path / "c.npy"))
    assert code == 3 and "DegenerateDataError" in err


def test_entry_points():
    v = subprocess.run([sys.executable, "-m", "mcstat_app", "--version"], capture_output=True, text=True)
    assert v.returncode == 0 and v.stdout.startswith(f"mcstat {mcstat.__version__}")
    script = os.path.join(os.path.dirname(sys.executable), "mcstat")
    if not os.path.exists(script):
        pytest.skip("no console script next to this interpreter (mcstat not pip-installed here)")
    p = subprocess.run([script, "plan", "--quick"], capture_output=True, text=True)
    assert p.returncode == 0 and "will run:" in p.stdout


def test_degenerate_samples_do_not_stop_the_run(tmp_path):
    """A tiny, distant emitter: U and C never hit it in a sample, so their
    tests cannot run; the run goes on, counts them as failed (not as
    rejections) and says so; a receiver facing away is left out."""
    scene = {"name": "tiny",
             "emitters": [{"vertices": [[100, 0, 50], [100.001, 0, 50], [100, 0.001, 50.0005]]}],
             "receivers": [{"point": [0, 0, 0], "normal": [0, 0, 1]},
                           {"name": "blind", "point": [0, 0, 0], "normal": [0, 0, -1]}],
             "studies": {"irradiance": {"runs": 20, "primary": 200, "secondary": 10},
                         "bugs": {"runs": 5, "budgets": [20, 200]}, "timing": {"enabled": False},
                         "sequential": {"runs": 5, "h0_runs": 20, "max_n": 2000, "pilot": 10000}}}
    path = tmp_path / "tiny.json"
    path.write_text(json.dumps(scene))
    code, out, err = run_cli("reproduce", "--scene", str(path), "--out", str(tmp_path / "o"), "--no-progress")
    assert code == 0, err
    res = strict_json(tmp_path / "o" / "results.json")
    rec = res["studies"]["irradiance"]["receivers"]
    assert [r["name"] for r in rec] == ["receiver 0"]
    u = rec[0]["one_sample"]["U"]
    assert u["rate"] is None and u["failed"] == 20 and u["rejections"] == 0
    assert rec[0]["one_sample"]["S"]["tests"] == 20
    assert any("no test of U, C could run" in f for f in res["findings"])
    dg = res["studies"]["diagnostics"]["receivers"][0]["estimators"]
    assert "constant" in dg["U"]["error"] and "error" not in dg["S"]  # recorded, and the run goes on
    assert any(s["target"] == "blind" and "horizon" in s["reason"] for s in res["plan"]["left_out"])
    assert "DegenerateDataError" in out
