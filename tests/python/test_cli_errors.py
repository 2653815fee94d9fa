"""The mcstat command never shows a traceback: a closed stdout, a missing
optional package, a missing, corrupt or unreadable input, an unwritable
output, a bad option and an internal error each give one line on stderr
saying what to do, with its own exit status (mcstat_app.errors)."""
import json
import os
import subprocess
import sys
import zipfile

import numpy as np
import pytest

from mcstat_app import errors as E

BLOCK = "import sys; sys.modules[{mod!r}] = None; "


def mcstat(*argv, pre="", stdout=subprocess.PIPE, env=None):
    """Runs the command in a fresh interpreter: (status, stdout, stderr).
    `pre` runs first (e.g. hides a package)."""
    code = pre + "import sys; from mcstat_app.cli import main; sys.exit(main(sys.argv[1:]))"
    p = subprocess.run([sys.executable, "-c", code, *map(str, argv)], stdout=stdout, stderr=subprocess.PIPE,
                       text=True, env=env)
    return p.returncode, p.stdout, p.stderr


def one_line(err):
    assert "Traceback" not in err, err
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    return lines[0]


@pytest.fixture
def samples(tmp_path):
    rng = np.random.default_rng(3)
    np.save(tmp_path / "x.npy", rng.normal(0.0, 1.0, 100))
    np.save(tmp_path / "y.npy", rng.normal(0.2, 1.0, 100))
    return tmp_path


@pytest.fixture
def stacks(tmp_path):
    rng = np.random.default_rng(5)
    np.save(tmp_path / "ref.npy", rng.normal(1.0, 0.1, (4, 6, 5)))
    np.save(tmp_path / "cand.npy", rng.normal(1.0, 0.1, (4, 6, 5)))
    return tmp_path


# -- stdout closed early -------------------------------------------------------

def _closed_pipe_run(*argv):
    """stdout is a pipe whose reader is already gone: the first write fails
    with EPIPE, whatever the timing (as `| head -1` once head has exited)."""
    r, w = os.pipe()
    os.close(r)
    try:
        p = subprocess.run([sys.executable, "-m", "mcstat_app", *map(str, argv)], stdout=w, stderr=subprocess.PIPE,
                           text=True)
    finally:
        os.close(w)
    return p.returncode, p.stderr


@pytest.mark.parametrize("argv", [("schema",), ("plan", "--quick"), ("--help",), ("test", "X", "Y", "--json"),
                                  ("test", "X", "Y", "--test", "ks")])
def test_broken_pipe(samples, argv):
    argv = [str(samples / "x.npy") if a == "X" else str(samples / "y.npy") if a == "Y" else a for a in argv]
    status, err = _closed_pipe_run(*argv)
    assert "Traceback" not in err and "BrokenPipe" not in err and "Exception ignored" not in err, err
    # argparse itself ignores a failed write of --help and exits 0
    assert status == (0 if argv == ["--help"] else E.EXIT_BROKEN_PIPE), err


def test_head_reads_the_first_line(samples):
    p = subprocess.run(f"'{sys.executable}' -m mcstat_app test '{samples / 'x.npy'}' '{samples / 'y.npy'}' --json "
                       "| head -1", shell=True, capture_output=True, text=True)
    assert p.returncode == 0 and p.stdout == "{\n" and "Traceback" not in p.stderr, p.stderr


# -- missing optional packages -------------------------------------------------

def test_png_without_pillow(stacks):
    png = stacks / "map.png"
    status, _, err = mcstat("image-test", "-r", stacks / "ref.npy", "-c", stacks / "cand.npy", "--png", png,
                            pre=BLOCK.format(mod="PIL"))
    line = one_line(err)
    assert status == E.EXIT_MISSING_PACKAGE
    assert "--png" in line and "pip install 'mcstat[image]'" in line and "pillow" in line
    assert not png.exists()


def test_exr_without_openexr(tmp_path):
    for i in range(2):
        (tmp_path / f"a{i}.exr").write_bytes(b"\x76\x2f\x31\x01" + b"\0" * 60)
    a = [tmp_path / "a0.exr", tmp_path / "a1.exr"]
    status, _, err = mcstat("image-test", "-r", *a, "-c", *a, pre=BLOCK.format(mod="OpenEXR"))
    line = one_line(err)
    assert status == E.EXIT_MISSING_PACKAGE and "pip install 'mcstat[image]'" in line and "OpenEXR" in line


def test_report_without_matplotlib(tmp_path):
    status, _, err = mcstat("reproduce", "--quick", "--out", tmp_path / "o", pre=BLOCK.format(mod="matplotlib"))
    line = one_line(err)
    assert status == E.EXIT_MISSING_PACKAGE and "pip install 'mcstat[report]'" in line and "--no-report" in line


def test_any_missing_module_is_one_line(samples):
    # a dependency missing from a broken install: still one line naming what to install
    pre = ("import sys, mcstat_app.samples as s\n"
           "def load(*a): import no_such_module_mcstat\n"
           "s.load_samples = load\n")
    status, _, err = mcstat("test", samples / "x.npy", pre=pre)
    line = one_line(err)
    assert status == E.EXIT_MISSING_PACKAGE and "pip install no_such_module_mcstat" in line


# -- bad input files -----------------------------------------------------------

def _corrupt_files(d):
    (d / "empty.npy").write_bytes(b"")
    (d / "garbage.npy").write_bytes(b"\x93NUMPY\x01\x00garbage")
    (d / "text.npy").write_text("not an array\n")
    good = d / "good.npz"
    np.savez(good, n=np.full((3, 4), 5.0), mean=np.zeros((3, 4)), M2=np.ones((3, 4)))
    raw = good.read_bytes()
    (d / "cut.npz").write_bytes(raw[: len(raw) // 2])
    bad = bytearray(raw)
    with zipfile.ZipFile(good) as z:  # flip bytes inside the first member's data: a CRC error on reading
        info = z.infolist()[0]
    start = info.header_offset + 30 + len(info.filename) + 20
    bad[start:start + 8] = b"\xff" * 8
    (d / "crc.npz").write_bytes(bytes(bad))
    (d / "binary.csv").write_bytes(b"\xff\xfe\x00\x01" * 10)
    (d / "scene.json").write_text('{"emitters": [')
    (d / "scene.toml").write_text("emitters = [[[0, 0")
    (d / "adir.npy").mkdir()


@pytest.mark.parametrize("argv", [
    ("test", "nope.npy"),
    ("test", "empty.npy"),
    ("test", "garbage.npy"),
    ("test", "text.npy"),
    ("test", "binary.csv"),
    ("test", "adir.npy"),
    ("plan", "nope.json"),
    ("plan", "scene.json"),
    ("plan", "scene.toml"),
    ("reproduce", "--scene", "scene.json", "--out", "o"),
    ("image-test", "-r", "nope.npy", "-c", "nope.npy"),
    ("image-test", "-r", "empty.npy", "-c", "empty.npy"),
    ("image-test", "-r", "garbage.npy", "-c", "garbage.npy"),
    ("image-test", "-r", "cut.npz", "-c", "good.npz"),
    ("image-test", "-r", "crc.npz", "-c", "good.npz"),
    ("image-test", "-r", "adir.npy", "-c", "good.npz"),
    ("image-test", "-r", "empty.npy", "text.npy", "-c", "empty.npy", "text.npy"),
])
def test_bad_input_file(tmp_path, argv):
    _corrupt_files(tmp_path)
    argv = [str(tmp_path / a) if ("." in a and not a.startswith("-")) or a == "o" else a for a in argv]
    status, _, err = mcstat(*argv)
    line = one_line(err)
    assert status == E.EXIT_INPUT, err
    assert line.startswith(f"mcstat {argv[0]}: ")
    assert any(os.path.basename(a) in line for a in argv[1:] if "." in os.path.basename(a)), line


def test_data_a_test_cannot_use(tmp_path):
    np.save(tmp_path / "c.npy", np.ones(10))
    status, _, err = mcstat("test", tmp_path / "c.npy")
    assert status == E.EXIT_INPUT and "DegenerateDataError" in one_line(err)


def test_corrupt_exr(tmp_path):
    pytest.importorskip("OpenEXR")
    for i in range(2):
        (tmp_path / f"a{i}.exr").write_bytes(b"\x76\x2f\x31\x01" + b"\0" * 60)
    a = [tmp_path / "a0.exr", tmp_path / "a1.exr"]
    status, _, err = mcstat("image-test", "-r", *a, "-c", *a)
    assert status == E.EXIT_INPUT and "a0.exr" in one_line(err)


# -- bad command lines ---------------------------------------------------------

@pytest.mark.parametrize("argv", [
    ("test", "X", "--test", "ks"),           # K-S needs two samples
    ("test", "X", "--test", "var"),          # one-sample var needs --sigma2
    ("test", "X", "--alpha", "2"),           # the library refuses alpha outside (0, 1)
    ("image-test", "-r", "R", "-c", "R", "--alpha", "0"),
])
def test_bad_arguments(samples, stacks, argv):
    argv = [str(samples / "x.npy") if a == "X" else str(stacks / "ref.npy") if a == "R" else a for a in argv]
    status, _, err = mcstat(*argv)
    assert status == E.EXIT_USAGE and one_line(err).startswith(f"mcstat {argv[0]}: "), err


def test_argparse_errors_are_usage():
    status, _, err = mcstat("test", "--no-such-option")
    assert status == E.EXIT_USAGE and "Traceback" not in err
    status, _, err = mcstat()
    assert status == E.EXIT_USAGE and "Traceback" not in err


# -- outputs that cannot be written -------------------------------------------

def test_unwritable_outputs(stacks):
    missing = stacks / "no" / "such" / "dir"
    base = ("image-test", "-r", stacks / "ref.npy", "-c", stacks / "cand.npy")
    for extra in (("--png", missing / "map.png"), ("--json", missing / "s.json")):
        status, _, err = mcstat(*base, *extra)
        assert status == E.EXIT_OUTPUT and extra[1].name in one_line(err), err
    (stacks / "afile").write_text("")
    status, _, err = mcstat("reproduce", "--no-report", "--out", stacks / "afile" / "sub")
    assert status == E.EXIT_OUTPUT and "afile" in one_line(err)


# -- internal errors -----------------------------------------------------------

def test_internal_error_is_one_line_unless_asked(samples):
    pre = ("import mcstat_app.samples as s\n"
           "def load(*a): raise RuntimeError('planted')\n"
           "s.load_samples = load\n")
    status, _, err = mcstat("test", samples / "x.npy", pre=pre)
    line = one_line(err)
    assert status == E.EXIT_INTERNAL and "RuntimeError: planted" in line and "MCSTAT_TRACEBACK=1" in line
    env = dict(os.environ, MCSTAT_TRACEBACK="1")
    status, _, err = mcstat("test", samples / "x.npy", pre=pre, env=env)
    assert status != 0 and "Traceback" in err and "planted" in err


def test_help_lists_the_exit_statuses():
    status, out, _ = mcstat("--help")
    assert status == 0
    for code in (E.EXIT_USAGE, E.EXIT_INPUT, E.EXIT_MISSING_PACKAGE, E.EXIT_OUTPUT, E.EXIT_INTERNAL,
                 E.EXIT_BROKEN_PIPE):
        assert f"\n  {code} " in out
    assert len({E.EXIT_REJECTED, E.EXIT_USAGE, E.EXIT_INPUT, E.EXIT_MISSING_PACKAGE, E.EXIT_OUTPUT,
                E.EXIT_INTERNAL, E.EXIT_INTERRUPTED, E.EXIT_BROKEN_PIPE}) == 8


def test_json_output_still_parses(samples):
    status, out, err = mcstat("test", samples / "x.npy", samples / "y.npy", "--json")
    assert status == 0 and json.loads(out)["method"]
