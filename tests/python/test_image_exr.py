"""`mcstat image-test` on renderers' own EXR outputs (mcstat_app.image_exr):
Mitsuba 3's moment AOVs to per-pixel summaries (exact against the closed
form n, m1, n (m2 - m1^2)), the float32 cancellation of m2 - m1^2 detected
and reported, several seeds as layers of one EXR, and clear errors for
truncated files, missing channels and the outputs that are refused."""
import sys

import numpy as np
import pytest

import mcstat
from mcstat import image as mi
from mcstat_app import image as app_image
from mcstat_app import image_exr
from cli_run import run_cli

OpenEXR = pytest.importorskip("OpenEXR")
SPP = 16


def write_exr(path, channels):
    with OpenEXR.File({"compression": OpenEXR.ZIP_COMPRESSION, "type": OpenEXR.scanlineimage},
                      {k: np.ascontiguousarray(v) for k, v in channels.items()}) as f:
        f.write(str(path))
    return str(path)


def moments_of(samples):
    """float32 m1 = mean(f), m2 = mean(f^2) per pixel of (spp, H, W, 3) samples, as the film stores them."""
    return samples.mean(axis=0).astype(np.float32), (samples ** 2).mean(axis=0).astype(np.float32)


def moment_channels(m1, m2, prefix="nested"):
    ch = {}
    for k, c in enumerate("XYZ"):
        ch[f"{prefix}.{c}"] = m1[..., k]
        ch[f"m2_{prefix}.{c}"] = m2[..., k]
        ch["RGB"[k]] = m1[..., k]  # the film's beauty (not read)
    return ch


def render_samples(rng, h=3, w=4, mean=1.0, sd=0.5):
    return rng.normal(mean, sd, size=(SPP, h, w, 3))


def test_moment_exr_to_summaries(tmp_path):
    rng = np.random.default_rng(31)
    x = render_samples(rng)
    m1, m2 = moments_of(x)
    p = write_exr(tmp_path / "m.exr", moment_channels(m1, m2))
    assert image_exr.kind_of(p) == "exr-moment"
    s = app_image.load_side(p, spp=SPP)
    assert isinstance(s, mi.Summary) and s.channel_names == ["X", "Y", "Z"]
    a1, a2 = m1.astype(np.float64), m2.astype(np.float64)
    np.testing.assert_array_equal(s.n, np.full(a1.shape, float(SPP)))
    np.testing.assert_array_equal(s.mean, a1)
    np.testing.assert_array_equal(s.m2, SPP * (a2 - a1 * a1))
    assert not s.unreliable.any()
    # the summaries are the samples' own (to float32 rounding)
    np.testing.assert_allclose(s.m2 / (SPP - 1), x.var(axis=0, ddof=1), rtol=1e-4)
    # luminance is the Y channel
    res = app_image.compare(p, p, spp=SPP)
    assert res.channel_names == ["Y"] and res.tested.all() and res.variance_lost == 0 and res.notes == []


def test_moment_exr_spp_per_side_and_cli(tmp_path):
    rng = np.random.default_rng(32)
    x, y = render_samples(rng), render_samples(rng, mean=1.0)
    y[:, 0, 0, :] += 3.0  # a planted difference at (0, 0)
    pr = write_exr(tmp_path / "r.exr", moment_channels(*moments_of(x)))
    pc = write_exr(tmp_path / "c.exr", moment_channels(*moments_of(y)))
    res = app_image.compare(pr, pc, spp=(SPP, SPP), channels="rgb")
    assert res.pixel_decision()[0, 0] == 1 and (res.pixel_decision() == 1).sum() == 1
    code, out, err = run_cli("image-test", "-r", pr, "-c", pc, "--spp", SPP, "--channels", "rgb")
    assert code == 0 and "channels X, Y, Z" in out, err
    code, _, err = run_cli("image-test", "-r", pr, "-c", pc)
    assert code != 0 and "r.exr" in err and "--spp" in err


def test_float32_cancellation_flagged(tmp_path):
    rng = np.random.default_rng(33)
    # pixel (0, 0): mean 1000, sd 1e-3: var = 1e-6 while m2 ~ 1e6 carries a
    # rounding error ~ 1e6 * 2^-24 = 0.06; the other pixels: mean 1, sd 0.5
    x = render_samples(rng)
    x[:, 0, 0, :] = rng.normal(1000.0, 1e-3, size=(SPP, 3))
    y = render_samples(rng)
    y[:, 0, 0, :] = rng.normal(1000.0, 1e-3, size=(SPP, 3))
    pr = write_exr(tmp_path / "r.exr", moment_channels(*moments_of(x)))
    pc = write_exr(tmp_path / "c.exr", moment_channels(*moments_of(y)))
    s = app_image.load_side(pr, spp=SPP)
    want = np.zeros(s.shape, dtype=bool)
    want[0, 0, :] = True
    np.testing.assert_array_equal(s.unreliable, want)
    res = app_image.compare(pr, pc, spp=SPP, channels="rgb")
    assert not res.tested[0, 0].any() and res.tested.sum() == res.tested.size - 3
    assert np.isnan(res.pvalue[0, 0]).all()
    assert res.variance_lost == 3
    note = "3 tests (pixel channels): variance lost to float32 cancellation in the input (m2 - m1^2); not tested"
    assert res.notes == [note] and ("note: " + note) in res.text()
    sm = res.summary()
    assert sm["variance_lost"] == 3 and sm["notes"] == [note] and sm["not_tested"] == 3
    lum = app_image.compare(pr, pc, spp=SPP)
    assert lum.notes == ["1 pixels: variance lost to float32 cancellation in the input (m2 - m1^2); not tested"]


def test_cancellation_bound():
    n = np.array([16.0])
    m1 = np.array([1.0])
    bound = image_exr.CANCELLATION_FACTOR * (1 + 4.0) * image_exr.EPS_FLOAT32 * 3.0  # m2 + 2 m1^2 ~ 3
    above, below = 1.0 + 1.01 * bound, 1.0 + 0.99 * bound
    assert not image_exr.cancellation_mask(m1, np.array([above]), n)[0]
    assert image_exr.cancellation_mask(m1, np.array([below]), n)[0]
    assert image_exr.cancellation_mask(m1, np.array([0.999]), n)[0]  # negative variance
    assert not image_exr.cancellation_mask(np.array([0.0]), np.array([0.0]), n)[0]  # black: zero, not lost
    # half channels: u = 2^-11
    assert image_exr.cancellation_mask(m1, np.array([1.001]), n, image_exr.EPS_HALF)[0]


def test_seed_layers(tmp_path):
    rng = np.random.default_rng(34)
    ref = rng.normal(1.0, 0.2, size=(12, 5, 6, 3)).astype(np.float32)
    cand = rng.normal(1.0, 0.2, size=(12, 5, 6, 3)).astype(np.float32)
    paths = []
    for name, data in (("r", ref), ("c", cand)):
        ch = {f"seed{k}.{c}": data[k, ..., j] for k in range(len(data)) for j, c in enumerate("RGB")}
        paths.append(write_exr(tmp_path / f"{name}.exr", ch))
    s = app_image.load_side(paths[0])
    assert isinstance(s, mi.Samples) and s.channel_names == ["R", "G", "B"]
    np.testing.assert_array_equal(s.data, ref)  # seed10 after seed9: numerical order
    res = app_image.compare(*paths)
    np.testing.assert_array_equal(res.pvalue, mi.compare(ref, cand, seed_axis=0).pvalue)


def test_seed_layers_missing_channel(tmp_path):
    im = np.ones((2, 3), dtype=np.float32)
    p = write_exr(tmp_path / "s.exr", {"seed0.R": im, "seed0.G": im, "seed1.R": im})
    with pytest.raises(mi.ImageInputError, match=r"s\.exr.*'seed1\.G' is missing"):
        app_image.load_side(p)


def test_moment_missing_channel(tmp_path):
    m = np.ones((2, 3, 3), dtype=np.float32)
    ch = moment_channels(m, m)
    del ch["m2_nested.Y"]
    p = write_exr(tmp_path / "m.exr", ch)
    with pytest.raises(mi.ImageInputError, match=r"m\.exr.*'m2_nested\.Y' is missing"):
        app_image.load_side(p, spp=SPP)


def test_truncated_exr(tmp_path):
    rng = np.random.default_rng(35)
    x = render_samples(rng, h=16, w=16)
    p = write_exr(tmp_path / "m.exr", moment_channels(*moments_of(x)))
    data = open(p, "rb").read()
    for cut in (len(data) // 2, 40):
        q = tmp_path / f"cut{cut}.exr"
        q.write_bytes(data[:cut])
        with pytest.raises(mi.ImageInputError, match=f"cut{cut}.exr"):
            app_image.load_side(str(q), spp=SPP)


def test_refused_outputs(tmp_path):
    im = np.ones((2, 3), dtype=np.float32)
    arnold = write_exr(tmp_path / "arnold.exr", {"R": im, "G": im, "B": im, "RGBA_variance.R": im})
    with pytest.raises(mi.ImageInputError, match=r"arnold\.exr.*RGBA_variance\.R.*normalisation"):
        app_image.load_side(arnold)
    cycles = write_exr(tmp_path / "cycles.exr", {"R": im, "Debug Sample Count.X": im})
    with pytest.raises(mi.ImageInputError, match=r"cycles\.exr.*sample-count"):
        app_image.load_side(cycles)
    two = moment_channels(np.ones((2, 3, 3), np.float32), np.ones((2, 3, 3), np.float32))
    two.update({k.replace("nested", "other"): v for k, v in two.items() if "nested" in k})
    p = write_exr(tmp_path / "two.exr", two)
    with pytest.raises(mi.ImageInputError, match=r"two\.exr.*one nested integrator"):
        app_image.load_side(p, spp=SPP)


def test_moment_exr_without_package(tmp_path, monkeypatch):
    m = np.ones((2, 3, 3), dtype=np.float32)
    p = write_exr(tmp_path / "m.exr", moment_channels(m, m))
    monkeypatch.setitem(sys.modules, "OpenEXR", None)
    with pytest.raises(app_image.MissingReaderError, match="pip install OpenEXR"):
        app_image.load_side(p, spp=SPP)


# ---- which layer of a multilayer EXR (one image per seed) -------------------------------
def blender_seeds(tmp_path, name, scale, k=8, layers=("ViewLayer.AO", "ViewLayer.Combined"), seed=0):
    """k files as Blender writes a multilayer EXR: an AO layer and the
    Combined render (its R, G, B scaled by `scale`), each seed's noise."""
    rng = np.random.default_rng(seed)
    paths = []
    for i in range(k):
        ch = {}
        for layer in layers:
            img = rng.normal(1.0, 0.05, size=(6, 7, 3)).astype(np.float32)
            if layer.endswith("Combined"):
                img = (img * scale).astype(np.float32)
            for c, comp in enumerate("RGB"):
                ch[f"{layer}.{comp}"] = img[..., c]
            ch[f"{layer}.A"] = np.ones((6, 7), np.float32)
        ch["ViewLayer.Depth.Z"] = np.zeros((6, 7), np.float32)
        paths.append(write_exr(tmp_path / f"{name}{i}.exr", ch))
    return paths


def test_blender_multilayer_reads_combined_and_says_so(tmp_path):
    ref = blender_seeds(tmp_path, "ref", 1.0, seed=1)
    cand = blender_seeds(tmp_path, "cand", 1.5, seed=2)
    code, out, _ = run_cli("image-test", "-r", *ref, "-c", *cand, "--fail-on-reject")
    # the AO layer is identical in distribution: reading it would say "equal"
    assert code == 1 and "different" in out, out
    assert "reference: read layer 'ViewLayer.Combined' of 8 EXR file(s)" in out
    assert "candidate: read layer 'ViewLayer.Combined'" in out
    code, out, _ = run_cli("image-test", "-r", *ref, "-c", *cand, "--layer", "ViewLayer.AO", "--fail-on-reject")
    assert code == 0 and "read layer 'ViewLayer.AO'" in out, out


def test_ambiguous_layers_are_refused_with_their_names(tmp_path):
    ref = blender_seeds(tmp_path, "ref", 1.0, layers=("A.Diffuse", "A.Glossy"), k=3)
    with pytest.raises(mi.ImageInputError, match=r"ambiguous .*'A.Diffuse', 'A.Glossy'.*--layer NAME"):
        app_image.load_side(ref)
    with pytest.raises(mi.ImageInputError, match="no colour layer 'B'"):
        app_image.load_side(ref, layer="B")
    two = blender_seeds(tmp_path, "two", 1.0, layers=("V1.Combined", "V2.Combined"), k=3)
    with pytest.raises(mi.ImageInputError, match="several Combined layers"):
        app_image.load_side(two)
    # unprefixed R, G, B (Mitsuba's default) win, and are named as such
    plain = [write_exr(tmp_path / f"p{i}.exr", {c: np.full((2, 3), 1.0 + i, np.float32) for c in "RGB"})
             for i in range(3)]
    side = app_image.load_side(plain)
    assert "unprefixed R, G, B" in side.source and side.data.shape == (3, 2, 3, 3)


def test_low_bit_depth_stacks_are_noted():
    rng = np.random.default_rng(0)
    a = rng.integers(0, 256, size=(8, 5, 5), dtype=np.uint8)
    b = rng.integers(0, 256, size=(8, 5, 5), dtype=np.uint8)
    res = mi.compare(a, b, seed_axis=0)
    assert any("uint8 values (8 bits): a display image" in n for n in res.notes)


def test_block_larger_than_the_image_is_refused():
    a = np.ones((4, 6, 7)) + np.random.default_rng(0).normal(0, 0.1, (4, 6, 7))
    with pytest.raises(mcstat.InvalidArgumentError, match="larger than the image"):
        mi.compare(a, a + 0.01, seed_axis=0, block=8)
    assert mi.compare(a, a + 0.01, seed_axis=0, block=7).block == 7


def test_one_word_for_each_channel():
    rng = np.random.default_rng(0)
    a, b = rng.normal(1, 0.1, (6, 5, 5, 3)), rng.normal(1, 0.1, (6, 5, 5, 3))
    assert mi.compare(a, b, seed_axis=0, channels="all").shape == mi.compare(a, b, seed_axis=0,
                                                                               channels="rgb").shape
    e_all = mi.equivalence(a, b, margin=0.5, seed_axis=0, channels="all")
    e_rgb = mi.equivalence(a, b, margin=0.5, seed_axis=0, channels="rgb")
    assert e_all.equivalent == e_rgb.equivalent


def test_ambiguous_seed_axis_names_the_command_line_option(tmp_path):
    p = tmp_path / "stack.npy"
    np.save(p, np.ones((32, 32, 16)))
    code, _, err = run_cli("image-test", "-r", p, "-c", p)
    assert code != 0 and "--seed-axis 0" in err, err
