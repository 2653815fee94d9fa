"""examples/dask/renderfarm.py on a real local Dask cluster (2 worker
processes): per-pixel accumulators rendered on the workers, shipped as
bytes, merged there, and tested per pixel on the client.

Checked: the ordered (fold) reduction equals one machine pushing the same
stacks bit for bit; the tree reduction equals the same tree on one machine
bit for bit and one machine's pushes to rounding; the merged moments equal
NumPy on the raw stacks; the correct renderer's per-pixel t tests against
the exact image reject at the nominal rate (binomial bounds); the planted
bug is found in nearly every pixel."""
import os
import sys

import cloudpickle
import numpy as np
import pytest
import scipy.stats as st
from dask.distributed import Client, LocalCluster

import mcstat

from conftest import ROOT

sys.path.insert(0, os.path.join(ROOT, "examples", "dask"))
import renderfarm as rf  # noqa: E402

# The worker processes cannot import the example by name: ship its functions by value.
cloudpickle.register_pickle_by_value(rf)

SHAPE = (12, 16)
TASKS, K, BATCH = 10, 8, 32  # 80 secondary estimates per pixel


@pytest.fixture(scope="module")
def client():
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0") as cluster, \
            Client(cluster) as c:
        yield c


@pytest.fixture(scope="module")
def farm(client):
    return {
        "tree": rf.render_farm(client, SHAPE, TASKS, K, BATCH, reduce="tree"),
        "fold": rf.render_farm(client, SHAPE, TASKS, K, BATCH, reduce="fold"),
        "bug": rf.render_farm(client, SHAPE, TASKS, K, BATCH, bug="barycentric"),
        "one": rf.single_machine(SHAPE, TASKS, K, BATCH),
    }


def test_workers_are_other_processes(client):
    pids = client.run(os.getpid)
    assert len(set(pids.values())) == 2 and os.getpid() not in pids.values()


def test_fixed_order_is_bit_for_bit(farm):
    (fold_img, fold_err), (one_img, one_err) = farm["fold"], farm["one"]
    assert fold_img.to_bytes() == one_img.to_bytes()
    assert fold_err.to_bytes() == one_err.to_bytes()
    tree_img, tree_err = farm["tree"]
    loc_img, loc_err = rf.local_reduce(SHAPE, TASKS, K, BATCH, reduce="tree")
    assert tree_img == loc_img and tree_err == loc_err


def test_tree_agrees_with_one_machine_to_rounding(farm):
    (tree_img, _), (one_img, _) = farm["tree"], farm["one"]
    assert (tree_img.n == TASKS * K).all() and (one_img.n == TASKS * K).all()
    assert np.max(np.abs(tree_img.mean / one_img.mean - 1)) <= 1e-15
    assert np.max(np.abs(tree_img.var / one_img.var - 1)) <= 4e-15
    assert (tree_img.min == one_img.min).all() and (tree_img.max == one_img.max).all()
    assert tree_img != one_img or TASKS < 3  # a different merge order does round differently


def test_merged_moments_match_numpy_on_the_raw_stacks(farm):
    raw = np.concatenate([rf.render_stack(t, SHAPE, K, BATCH) for t in range(TASKS)])
    img, err = farm["tree"]
    np.testing.assert_allclose(img.mean, raw.mean(axis=0), rtol=1e-14)
    np.testing.assert_allclose(img.var, raw.var(axis=0, ddof=1), rtol=1e-12)
    exact = rf.exact_image(SHAPE)
    np.testing.assert_allclose(err.mean, (raw - exact).mean(axis=0), rtol=1e-12, atol=1e-16)


def test_per_pixel_tests_calibration_and_power(farm):
    _, err = farm["tree"]
    alpha = 0.05
    r = mcstat.t_test(err, mu=0.0, alpha=alpha)
    P = err.size
    lo, hi = st.binom.ppf([0.0005, 0.9995], P, alpha)
    assert lo <= r.reject.sum() <= hi, (r.reject.sum(), lo, hi)
    # the same numbers as each pixel's own accumulator, tested alone
    assert r[3, 5]._raw() == mcstat.t_test(err[3, 5], mu=0.0, alpha=alpha)._raw()
    # the barycentric bug: detected against the correct renderer, and against the exact image
    bug_img, bug_err = farm["bug"]
    welch = mcstat.t_test(bug_img, farm["tree"][0], alpha=alpha)
    assert welch.reject.mean() > 0.9
    assert mcstat.t_test(bug_err, mu=0.0, alpha=alpha).reject.mean() > 0.9
    # the two reductions of the same samples: variance ratio 1 to rounding, never rejected
    one_img, _ = farm["one"]
    f = mcstat.var_test(one_img, farm["tree"][0])
    assert np.allclose(f.statistic, 1.0, rtol=1e-14) and not f.reject.any()


def test_example_main_runs(capsys):
    assert rf.main(["--workers", "2", "--tasks", "4", "--shape", "4", "6", "--k", "4", "--batch", "16"]) == 0
    out = capsys.readouterr().out
    assert "tree-merged vs one machine" in out and "pixels rejected" in out
