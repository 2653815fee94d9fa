"""The demo suite's warp checks (cases.py): each a statistical test under the suite's budget."""
import pytest

import cases

MINE = [c for c in cases.CASES if c[1] == "warp"]


@pytest.mark.mcstat
@pytest.mark.parametrize("case", MINE, ids=[c[0] for c in MINE])
def test_warp(case):
    case_id, _, run = case
    run(**cases.planted(case_id))
