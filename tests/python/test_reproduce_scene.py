"""Scene files of `mcstat reproduce`: the schema, the validator, the built-in
scene, the examples, the planner's rules, and clear errors for bad files."""
import copy
import json
import os

import numpy as np
import pytest

from conftest import ROOT
from mcstat import estimators as est
from mcstat_app.reproduce import PAPER_SCENE, Plan, SceneError, load_scene, parse_scene
from mcstat_app.reproduce.scene import schema, schema_text
from mcstat_app.reproduce.validate import Validator

SCENES = os.path.join(ROOT, "examples", "scenes")


def scene_with(**changes):
    d = copy.deepcopy(PAPER_SCENE)
    for path, value in changes.items():
        node, keys = d, path.split("__")
        for k in keys[:-1]:
            node = node[int(k)] if k.isdigit() else node.setdefault(k, {})
        last = keys[-1]
        if value is DELETE:
            del node[int(last) if last.isdigit() else last]
        elif last.isdigit():
            node[int(last)] = value
        else:
            node[last] = value
    return d


DELETE = object()


def errors_of(doc):
    with pytest.raises(SceneError) as e:
        parse_scene(doc, "s.json")
    return e.value.errors


def test_schema_file_is_the_package_schema():
    # examples/scenes/schema.json is a link to the package's schema: one copy
    with open(os.path.join(SCENES, "schema.json"), encoding="utf-8") as f:
        assert f.read() == schema_text()


def test_validator_refuses_keywords_it_does_not_check():
    with pytest.raises(ValueError, match="unsupported keywords.*pattern"):
        Validator({"type": "object", "properties": {"x": {"type": "string", "pattern": "a+"}}})


def test_builtin_scene_is_libmcest_paper_scene_and_paper_toml():
    sc = load_scene(None)
    ref = est.paper_scene()
    assert np.array_equal(sc.triangles[0], ref["triangle"])
    assert np.array_equal(sc.receivers[0]["point"], ref["point"])
    assert np.array_equal(sc.receivers[0]["normal"], ref["normal"]) and sc.radiances[0] == ref["radiance"]
    toml = load_scene(os.path.join(SCENES, "paper.toml"))
    assert toml.data == sc.data


@pytest.mark.parametrize("name", ["paper.toml", "no_brdf.json", "two_triangles.toml", "minimal.json"])
def test_example_scenes_parse(name):
    sc = load_scene(os.path.join(SCENES, name))
    assert sc.data["studies"]["irradiance"]["alpha"] > 0  # defaults filled in
    json.dumps(sc.data)  # JSON-ready


def test_defaults_come_from_the_schema():
    sc = load_scene(os.path.join(SCENES, "minimal.json"))
    s = schema()["$defs"]
    assert sc.estimators == ["U", "C", "A", "S"] and sc.trusted == "S" and sc.brdfs == []
    for study in ("irradiance", "sampling", "radiance", "bugs", "timing"):
        for field, spec in s[f"{study}_study"]["properties"].items():
            if "default" in spec:
                assert sc.studies[study][field] == spec["default"], (study, field)


def test_trusted_defaults_to_the_best_listed_estimator():
    assert parse_scene(scene_with(estimators=["U", "C"], trusted=DELETE)).trusted == "C"
    assert parse_scene(scene_with(estimators=["A", "U"], trusted=DELETE)).trusted == "A"


BAD = [
    (dict(brdfs__0__alpha_x=-2), "scene.brdfs[0].alpha_x: expected a number >= 0.0001 and <= 10, got -2"),
    (dict(brdfs__1__n_u="many"), "scene.brdfs[1].n_u: expected a number >= 0 and <= 1e+07, got 'many'"),
    (dict(brdfs__1__model="phong"), "scene.brdfs[1].model: expected one of 'ward', 'ashikhmin_shirley', got 'phong'"),
    (dict(brdfs__0__rho_s=DELETE), "scene.brdfs[0].rho_s: required field missing; expected a number >= 0"),
    (dict(brdfs__0__outgoing=[1, 0, -1]), "scene.brdfs[0].outgoing: expected a direction above the surface (z > 0)"),
    (dict(brdfs__0__outgoing={"theta": 95}), "scene.brdfs[0].outgoing.theta: expected a number >= 0 and < 90, got 95"),
    (dict(brdfs__0__outgoing="up"), "scene.brdfs[0].outgoing: expected a list of 3 numbers or an object"),
    (dict(brdfs__1__name="ward"), "scene.brdfs[1].name: 'ward' is also the name of brdfs[0]"),
    (dict(emitters=[]), "scene.emitters: expected a list of at least 1, got 0 items"),
    (dict(emitters__0__vertices=[[0, 0, 1], [1, 1, 1], [2, 2, 1]]),
     "scene.emitters[0].vertices: expected the corners of a triangle"),
    (dict(emitters__0__vertices__1=[1, 2]), "scene.emitters[0].vertices[1]: expected a list of 3 numbers, got 2 items"),
    (dict(emitters__0__radiance=-1), "scene.emitters[0].radiance: expected a number >= 0, got -1"),
    (dict(receivers__0__normal=[0, 0, 0]), "scene.receivers[0].normal: expected a non-zero vector, got [0, 0, 0]"),
    (dict(receivers=DELETE), "scene.receivers: required field missing"),
    (dict(estimators=["U", "X"]), "scene.estimators[1]: expected one of 'U', 'C', 'A', 'S', got 'X'"),
    (dict(estimators=["U", "U"]), "scene.estimators[1]: 'U' appears twice"),
    (dict(estimators=["U", "C"], trusted="S"), "scene.trusted: expected one of the scene's estimators (U, C), got 'S'"),
    (dict(studies__irradiance__rnus=3), "scene.studies.irradiance.rnus: unknown field; expected one of enabled, alpha"),
    (dict(studies__irradiance__alpha=1.5), "scene.studies.irradiance.alpha: expected a number > 0 and < 1, got 1.5"),
    (dict(studies__irradiance__runs=2.5), "scene.studies.irradiance.runs: expected an integer >= 1"),
    (dict(studies__irradiance__primary=10), "scene.studies.irradiance.primary: expected at least `secondary` (50)"),
    (dict(studies__sampling__sizes=[100, 10]), "scene.studies.sampling.sizes: expected increasing numbers, got [100, 10]"),
    (dict(studies__radiance__brdfs=["wadr"]), "scene.studies.radiance.brdfs[0]: expected the name of one of the scene's BRDFs ('ward', 'ashikhmin_shirley'), got 'wadr'"),
    (dict(studies__bugs__bugs=["typo"]), "scene.studies.bugs.bugs[0]: expected one of 'no_cosine', 'barycentric', 'no_jacobian'"),
    (dict(studies__timing__enabled="yes"), "scene.studies.timing.enabled: expected true or false, got 'yes'"),
    (dict(studies__sampler_bugs__bugs=["typo"]), "scene.studies.sampler_bugs.bugs[0]: expected one of 'roughness', 'axes_swapped', 'phi_half', 'jacobian'"),
    (dict(studies__sampler_bugs__sizes=[300, 100]), "scene.studies.sampler_bugs.sizes: expected increasing numbers, got [300, 100]"),
    (dict(studies__sampler_bugs__brdfs=["nope"]), "scene.studies.sampler_bugs.brdfs[0]: expected the name of one of the scene's BRDFs ('ward', 'ashikhmin_shirley'), got 'nope'"),
    (dict(colour="red"), "scene.colour: unknown field; expected one of name, description, emitters"),
]


@pytest.mark.parametrize("changes,message", BAD, ids=[m.split(":")[0] for _, m in BAD])
def test_bad_scenes_name_the_field(changes, message):
    errs = errors_of(scene_with(**changes))
    assert any(e.startswith(message) for e in errs), errs


def test_every_problem_is_reported_at_once():
    errs = errors_of(scene_with(brdfs__0__alpha_x=-2, estimators=["U", "X"], studies__bugs__runs=0))
    assert len(errs) == 3
    msg = str(SceneError(errs, "s.json"))
    assert msg.startswith("s.json: 3 problems:") and "scene.studies.bugs.runs" in msg


def test_not_finite_and_not_an_object():
    assert errors_of(scene_with(emitters__0__radiance=float("nan"))) == [
        "scene.emitters[0].radiance: expected a number >= 0, got nan"]
    assert errors_of([1, 2]) == ["scene: expected an object (a table), got [1, 2]"]


def test_file_errors(tmp_path):
    cases = {
        "a.json": ('{"emitters": [}', "JSON syntax error at line 1, column 15"),
        "b.toml": ("emitters = [\n", "TOML syntax error"),
        "c.yaml": ("emitters: []", "expected a .json or .toml file, got '.yaml'"),
    }
    for name, (text, msg) in cases.items():
        p = tmp_path / name
        p.write_text(text)
        with pytest.raises(SceneError, match=msg) as e:
            load_scene(str(p))
        assert str(e.value).startswith(str(p))
    with pytest.raises(SceneError, match="cannot read the scene file"):
        load_scene(str(tmp_path / "missing.json"))


# -- the planner ---------------------------------------------------------------

def steps(plan, study):
    return [s for s in plan.steps if s["study"] == study]


def left(plan, study):
    return [s for s in plan.left_out if s["study"] == study]


def test_plan_of_the_paper_scene():
    p = Plan(load_scene(None))
    assert [s["study"] for s in p.steps] == ["irradiance", "irradiance", "irradiance", "sampling", "sampling",
                                             "radiance", "bugs", "sampler_bugs", "sampler_bugs", "renderer_check",
                                             "renderer_check", "sequential", "timing", "timing",
                                             "diagnostics", "diagnostics"]
    # diagnostics: the receiver's irradiance estimators and the BRDF 3.3 tests
    assert [s["target"] for s in steps(p, "diagnostics")] == ["origin", "ward"]
    assert [s["target"] for s in left(p, "diagnostics")] == ["ashikhmin_shirley"]
    assert [s["section"] for s in steps(p, "sampler_bugs")] == ["3.2+", "3.2+"]
    assert "Lambert" in steps(p, "irradiance")[0]["what"]
    # beyond the paper: equivalence and sample sizes against Lambert
    assert "equivalence (TOST)" in steps(p, "irradiance")[1]["what"]
    assert "0.1% bias at power 0.9" in steps(p, "irradiance")[1]["what"]
    # 3.3 on Ward only, as in the paper, and said so
    assert [s["target"] for s in left(p, "radiance")] == ["ashikhmin_shirley"]
    assert p.quick_changes == [] and not p.quick


def test_plan_quick_caps():
    p = Plan(load_scene(None), quick=True)
    assert p.params["sampling"]["sizes"][-1] == 10000 and p.params["radiance"]["directions"] == 200
    assert p.params["sampler_bugs"]["sizes"][-1] == 3000 and p.params["sampler_bugs"]["runs"] == 20
    assert any("sampling.sizes" in c for c in p.quick_changes)
    assert load_scene(None).studies["sampling"]["sizes"][-1] == 100000  # the scene itself is unchanged


def test_plan_rules():
    # no BRDF: 3.2 and 3.3 left out, with the reason
    p = Plan(load_scene(os.path.join(SCENES, "minimal.json")))
    assert not steps(p, "sampling") and not steps(p, "radiance") and not steps(p, "sampler_bugs")
    assert [s["reason"] for s in left(p, "sampling") + left(p, "radiance") + left(p, "sampler_bugs")] == \
        ["the scene has no BRDFs"] * 3
    # 3.2+ on the listed BRDFs only, the others left out with the reason
    p = Plan(parse_scene(scene_with(studies__sampler_bugs__brdfs=["ward"])))
    assert [s["target"] for s in steps(p, "sampler_bugs")] == ["ward"]
    assert left(p, "sampler_bugs")[0]["reason"] == "not listed in studies.sampler_bugs.brdfs"
    # two triangles: no one-sample test against Lambert
    p = Plan(load_scene(os.path.join(SCENES, "two_triangles.toml")))
    assert all("Lambert" not in s["what"] for s in steps(p, "irradiance"))
    assert any("2 emitter triangles" in s["reason"] for s in left(p, "irradiance"))
    assert any(s["what"].startswith("equivalence with Lambert") and "exact irradiance" in s["reason"]
               for s in left(p, "irradiance"))
    assert all(r["lambert"] is None for r in p.receivers)
    # no A: no bugs; A trusted: no bugs
    p = Plan(parse_scene(scene_with(estimators=["U", "S"])))
    assert not steps(p, "bugs") and "does not list estimator A" in left(p, "bugs")[0]["reason"]
    p = Plan(parse_scene(scene_with(estimators=["A", "U"], trusted="A")))
    assert not steps(p, "bugs") and "trusted estimator is A" in left(p, "bugs")[0]["reason"]
    # a receiver that sees nothing
    p = Plan(parse_scene(scene_with(receivers__0__normal=[0, 0, -1])))
    assert not steps(p, "irradiance") and "horizon" in left(p, "irradiance")[0]["reason"]
    # diagnostics: no BRDF, a blind receiver, switched off
    p = Plan(load_scene(os.path.join(SCENES, "minimal.json")))
    assert [s["reason"] for s in left(p, "diagnostics")] == ["the scene has no BRDFs"]
    p = Plan(parse_scene(scene_with(receivers__0__normal=[0, 0, -1])))
    assert "horizon" in left(p, "diagnostics")[0]["reason"]
    p = Plan(parse_scene(scene_with(studies__diagnostics__enabled=False)))
    assert not steps(p, "diagnostics")
    assert Plan(load_scene(None), quick=True).params["diagnostics"]["n"] == 20000
    # switched off
    p = Plan(parse_scene(scene_with(studies__bugs__enabled=False)))
    assert left(p, "bugs")[0]["reason"] == "disabled in the scene (studies.bugs.enabled = false)"
    text = p.text()
    assert "left out:" in text and "studies.bugs.enabled = false" in text
