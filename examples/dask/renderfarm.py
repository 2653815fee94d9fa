# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""A render farm on Dask: per-pixel accumulators, shipped, merged, tested.

The "renderer" estimates the irradiance image of a receiver plane lit by
the paper's triangular emitter (mcstat.estimators): pixel (i, j) is a
receiver point, its exact value `irradiance_exact`.  The work is cut into
tasks; task t renders, for every pixel, k secondary estimates (means of
`batch` primary estimates, numbers first_index = t*k*batch on of the
pixel's own random stream), so a task is a pure function of its number and
any worker may run it.  Each task pushes its stack into two
`mcstat.MomentsArray`s - the image and its error (estimate - exact) - and
returns their bytes (96 per pixel each): that is all that crosses the
network.  The client merges the task results by a pairwise tree on the
workers (or a left fold, "fold", in task order) and runs the per-pixel tests
on the merged arrays:

  * t test of mean error = 0 per pixel (is the renderer unbiased?);
  * Welch test of a planted-bug renderer against the correct one per pixel.

Merging is exact arithmetic on moments, so a fixed merge order is
reproducible bit for bit: the fold equals one machine pushing every task's
stack in order, and the tree equals the same tree merged on one machine.

Run:  python examples/dask/renderfarm.py [--workers 2] [--tasks 16]
"""
from __future__ import annotations

import argparse
import time
from typing import List, Optional, Sequence, Tuple

import numpy as np

import mcstat
from mcstat import estimators as est

# The paper's emitter over a receiver plane z = 0 facing +z.
TRIANGLE = est.paper_scene()["triangle"]
NORMAL = np.array([0.0, 0.0, 1.0])
EXTENT = (1.2, 0.9)  # half-widths of the receiver rectangle in x and y


def receiver_points(shape: Tuple[int, int]) -> np.ndarray:
    """Pixel centres on the plane z = 0, shape (H, W, 3)."""
    h, w = shape
    xs = (np.arange(w) + 0.5) / w * 2 * EXTENT[0] - EXTENT[0]
    ys = (np.arange(h) + 0.5) / h * 2 * EXTENT[1] - EXTENT[1]
    gx, gy = np.meshgrid(xs, ys)
    return np.stack([gx, gy, np.zeros_like(gx)], axis=-1)


def exact_image(shape: Tuple[int, int]) -> np.ndarray:
    """The exact irradiance per pixel (Lambert's formula)."""
    pts = receiver_points(shape)
    return np.array([[est.irradiance_exact(triangle=TRIANGLE, point=p, normal=NORMAL) for p in row] for row in pts])


def render_stack(task: int, shape: Tuple[int, int], k: int, batch: int, method: str = "A",
                 bug: Optional[str] = None, seed: int = 1) -> np.ndarray:
    """Task `task`'s k secondary estimates per pixel, shape (k, H, W).

    Pixel p draws from stream seed * 2**32 + p; task t takes estimates
    t*k*batch .. (t+1)*k*batch - 1 of it, so tasks never overlap and the
    numbers do not depend on which worker renders them."""
    pts = receiver_points(shape)
    h, w = shape
    out = np.empty((k, h, w))
    for i in range(h):
        for j in range(w):
            plan = est.IrradiancePlan(triangle=TRIANGLE, point=pts[i, j], normal=NORMAL)
            prim = plan.estimates(method, k * batch, seed=seed * 2**32 + i * w + j, bug=bug,
                                  first_index=task * k * batch, threads=1)
            out[:, i, j] = mcstat.batch_means(prim, batch)
    return out


def render_task(task: int, shape: Tuple[int, int], k: int, batch: int, method: str = "A",
                bug: Optional[str] = None, seed: int = 1) -> Tuple[bytes, bytes]:
    """A worker's job: render one task and return (image bytes, error bytes)."""
    stack = render_stack(task, shape, k, batch, method, bug, seed)
    image = mcstat.MomentsArray(shape).push(stack)
    error = mcstat.MomentsArray(shape).push(stack - exact_image(shape))
    return image.to_bytes(), error.to_bytes()


def merge_parts(a: Tuple[bytes, bytes], b: Tuple[bytes, bytes], shape: Tuple[int, int]) -> Tuple[bytes, bytes]:
    """Merges two task results (a first: the order is part of the result's bits)."""
    return tuple((mcstat.MomentsArray.from_bytes(x, shape) + mcstat.MomentsArray.from_bytes(y, shape)).to_bytes()
                 for x, y in zip(a, b))


def reduce_pairs(parts: Sequence, merge, reduce: str = "tree"):
    """Reduces parts in a fixed order: "tree" pairs (0,1), (2,3), ... level by
    level (an odd last one moves up unchanged); "fold" merges left to right.
    `merge(a, b)` may return a value or a Dask future: the same order either way."""
    parts = list(parts)
    if reduce == "fold":
        acc = parts[0]
        for p in parts[1:]:
            acc = merge(acc, p)
        return acc
    if reduce != "tree":
        raise ValueError(f"reduce must be 'tree' or 'fold', got {reduce!r}")
    while len(parts) > 1:
        nxt = [merge(parts[i], parts[i + 1]) for i in range(0, len(parts) - 1, 2)]
        if len(parts) % 2:
            nxt.append(parts[-1])
        parts = nxt
    return parts[0]


def render_farm(client, shape: Tuple[int, int], tasks: int, k: int, batch: int, method: str = "A",
                bug: Optional[str] = None, seed: int = 1,
                reduce: str = "tree") -> Tuple[mcstat.MomentsArray, mcstat.MomentsArray]:
    """Renders `tasks` tasks on the cluster, merges them there, returns (image, error)."""
    futures = [client.submit(render_task, t, shape, k, batch, method, bug, seed, pure=False) for t in range(tasks)]
    total = reduce_pairs(futures, lambda a, b: client.submit(merge_parts, a, b, shape, pure=False), reduce)
    image, error = total.result()
    return mcstat.MomentsArray.from_bytes(image, shape), mcstat.MomentsArray.from_bytes(error, shape)


def single_machine(shape: Tuple[int, int], tasks: int, k: int, batch: int, method: str = "A",
                   bug: Optional[str] = None, seed: int = 1) -> Tuple[mcstat.MomentsArray, mcstat.MomentsArray]:
    """The same tasks pushed one after another into one pair of accumulators."""
    image, error = mcstat.MomentsArray(shape), mcstat.MomentsArray(shape)
    exact = exact_image(shape)
    for t in range(tasks):
        stack = render_stack(t, shape, k, batch, method, bug, seed)
        image.push(stack)
        error.push(stack - exact)
    return image, error


def local_reduce(shape: Tuple[int, int], tasks: int, k: int, batch: int, method: str = "A",
                 bug: Optional[str] = None, seed: int = 1, reduce: str = "tree"):
    """The farm's reduction run on one machine (same tasks, same merge order)."""
    parts = [render_task(t, shape, k, batch, method, bug, seed) for t in range(tasks)]
    image, error = reduce_pairs(parts, lambda a, b: merge_parts(a, b, shape), reduce)
    return mcstat.MomentsArray.from_bytes(image, shape), mcstat.MomentsArray.from_bytes(error, shape)


def main(argv: Optional[List[str]] = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--tasks", type=int, default=16)
    ap.add_argument("--shape", type=int, nargs=2, default=(24, 32), metavar=("H", "W"))
    ap.add_argument("--k", type=int, default=8, help="secondary estimates per pixel per task")
    ap.add_argument("--batch", type=int, default=64, help="primary estimates per secondary estimate")
    ap.add_argument("--bug", default="barycentric", choices=["no_cosine", "barycentric", "no_jacobian"])
    ap.add_argument("--alpha", type=float, default=0.01)
    args = ap.parse_args(argv)
    from dask.distributed import Client, LocalCluster

    shape = tuple(args.shape)
    with LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True,
                      dashboard_address=":0") as cluster, Client(cluster) as client:
        t0 = time.perf_counter()
        image, error = render_farm(client, shape, args.tasks, args.k, args.batch)
        bug_image, _ = render_farm(client, shape, args.tasks, args.k, args.batch, bug=args.bug)
        t1 = time.perf_counter()
    ref_image, _ = single_machine(shape, args.tasks, args.k, args.batch)
    t2 = time.perf_counter()
    P = image.size
    dmean = np.max(np.abs(image.mean / ref_image.mean - 1))
    dvar = np.max(np.abs(image.var / ref_image.var - 1))
    print(f"{P} pixels x {int(image.n.flat[0])} secondary estimates, {args.tasks} tasks on {args.workers} workers: "
          f"{t1 - t0:.2f} s (two renderers); one machine, one renderer: {t2 - t1:.2f} s")
    print(f"tree-merged vs one machine: max relative difference mean {dmean:.2g}, variance {dvar:.2g}")
    unbiased = mcstat.t_test(error, mu=0.0, alpha=args.alpha)
    print(f"correct renderer, t test of mean error = 0 per pixel at alpha={args.alpha:g}: "
          f"{int(unbiased.reject.sum())} of {P} pixels rejected (expected by chance: {args.alpha * P:.1f})")
    welch = mcstat.t_test(bug_image, image, alpha=args.alpha)
    dec = welch.decision
    print(f"'{args.bug}' renderer vs correct, Welch per pixel: {int(welch.reject.sum())} of {P} pixels differ "
          f"({int((dec == 'less').sum())} darker, {int((dec == 'greater').sum())} brighter)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
