"""mcstat reproduce's table of studies is the one registry: the schema,
the plan, the seed streams and the report follow it."""
import importlib

import pytest

from mcstat_app.reproduce import Plan, load_scene
from mcstat_app.reproduce.context import Context
from mcstat_app.reproduce.scene import schema
from mcstat_app.reproduce.studies import BY_KEY, STUDIES


def test_table_is_consistent():
    keys = [s.key for s in STUDIES]
    assert len(set(keys)) == len(keys)
    streams = [s.stream for s in STUDIES]
    assert len(set(streams)) == len(streams) and all(n > 0 for n in streams)
    assert len({s.section for s in STUDIES}) == len(STUDIES)
    for s in STUDIES:
        mod = s.module()
        assert callable(mod.run) and callable(mod.findings), s.key


def test_schema_has_one_part_per_study_and_no_other():
    sc = schema()
    props = sc["properties"]["studies"]["properties"]
    assert set(props) == set(BY_KEY)
    for key, ref in props.items():
        assert ref == {"$ref": f"#/$defs/{BY_KEY[key].schema}"}
    study_defs = {d for d in sc["$defs"] if d.endswith("_study")}
    assert study_defs == {s.schema for s in STUDIES}


def test_plan_and_streams_follow_the_table():
    plan = Plan(load_scene(None), quick=True)
    for step in plan.steps + plan.left_out:
        assert step["section"] == BY_KEY[step["study"]].section
    assert {s["study"] for s in plan.steps} == set(BY_KEY)  # the paper scene runs every study
    # the stream numbers are fixed: the seeds of a run depend on them
    ctx = Context(1, progress=False)
    assert ctx.stream("irradiance", 0) == ctx.stream("irradiance", 0)
    assert {k: BY_KEY[k].stream for k in BY_KEY} == {"irradiance": 1, "sampling": 2, "radiance": 3, "bugs": 4,
                                                     "timing": 5, "diagnostics": 6, "sampler_bugs": 7, "renderer_check": 8,
                                                     "sequential": 9}


def test_report_parts_resolve():
    pytest.importorskip("matplotlib")
    for s in STUDIES:
        assert callable(s.report_part()), s.key
    importlib.import_module("mcstat_app.reproduce.report")
