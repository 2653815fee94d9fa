"""The demo suite's bsdf checks (cases.py): each a statistical test under the suite's budget."""
import pytest

import cases

MINE = [c for c in cases.CASES if c[1] == "bsdf"]


@pytest.mark.mcstat
@pytest.mark.parametrize("case", MINE, ids=[c[0] for c in MINE])
def test_bsdf(case):
    case_id, _, run = case
    run(**cases.planted(case_id))
