"""mcstat reproduce's progress bars follow the estimated work (reproduce/cost.py),
not the count of steps: each bar ends exactly at its total, and a step that does
more work advances it more (the first K-S test at a size simulates the null; a
larger budget draws more estimates)."""
import contextlib
import copy
import io
import json

import pytest

from mcstat_app.cli import main
from mcstat_app.reproduce import PAPER_SCENE, context


class Recorder:
    bars = []

    def __init__(self, total, desc):
        self.total, self.desc, self.steps = total, desc, []
        Recorder.bars.append(self)

    def update(self, n=1):
        self.steps.append(n)

    def set_postfix_str(self, s):
        pass

    def close(self):
        pass

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        pass


@pytest.fixture(scope="module")
def bars(tmp_path_factory):
    d = tmp_path_factory.mktemp("progress")
    scene = copy.deepcopy(PAPER_SCENE)
    scene["brdfs"] = [b for b in scene["brdfs"] if b["name"] == "ward"]
    scene["studies"] = {s: {"enabled": False} for s in ("irradiance", "radiance", "diagnostics", "timing",
                                                        "sampler_bugs", "renderer_check")}
    scene["studies"]["sampling"] = {"sizes": [30, 3000], "runs": 3, "n_sim": 2000, "histogram_size": 2000}
    scene["studies"]["bugs"] = {"budgets": [20, 2000], "runs": 5}
    scene["studies"]["sequential"] = {"runs": 3, "h0_runs": 20, "max_n": 1000, "pilot": 10000}
    path = d / "scene.json"
    path.write_text(json.dumps(scene))
    Recorder.bars = []
    mp = pytest.MonkeyPatch()
    mp.setattr(context.Context, "bar", lambda self, total, desc: Recorder(total, desc))
    try:
        with contextlib.redirect_stdout(io.StringIO()):
            assert main(["reproduce", "--scene", str(path), "--out", str(d / "out"), "--no-report",
                         "--no-progress"]) == 0
    finally:
        mp.undo()
    return {b.desc: b for b in Recorder.bars}


def test_every_bar_ends_at_its_total(bars):
    assert {"3.2 ward", "3.4 origin", "3.4+ origin"} <= set(bars)
    for b in bars.values():
        assert sum(b.steps) == pytest.approx(b.total, rel=1e-12), b.desc


def test_sampling_steps_weighted_by_work(bars):
    s = bars["3.2 ward"].steps
    # 3 runs at n = 30 (exact p-values), 3 at n = 3000 (simulated: the first run
    # simulates the null), then the figure-6 histograms
    assert len(s) == 7
    assert s[0] == s[1] == s[2]
    assert s[3] > 2 * s[4] and s[4] == s[5]
    assert s[4] > 10 * s[0]
    from mcstat_app.reproduce import cost

    assert s[3] == pytest.approx(3000 * cost.DIRECTION_PAIR + cost.ks(3000, 3000, 2000), rel=1e-12)


def test_bug_steps_weighted_by_budget(bars):
    s = bars["3.4 origin"].steps
    assert len(s) == 8  # 2 budgets x (no bug + 3 bugs)
    assert min(s[4:]) > 20 * max(s[:4])
