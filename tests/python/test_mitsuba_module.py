"""mcstat.mitsuba without Mitsuba: importing mcstat or mcstat.mitsuba
imports neither Mitsuba nor Dr.Jit (nor sets DRJIT_LIBLLVM_PATH), and a
check called where Mitsuba is missing raises ImportError naming the extra.
The checks themselves run on Mitsuba in `make mitsuba-test`
(examples/mitsuba/test_shipped_adapters.py).  Each case runs in a fresh
interpreter: this process may have imported Mitsuba already."""
import subprocess
import sys
import textwrap


def run(code):
    r = subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stdout + r.stderr
    return r.stdout


def test_import_is_lazy():
    out = run("""
        import os, sys
        os.environ.pop("DRJIT_LIBLLVM_PATH", None)
        import mcstat, mcstat.mitsuba, mcstat.mitsuba.fixtures
        print(sorted(m for m in sys.modules if m.split(".")[0] in ("mitsuba", "drjit")),
              "DRJIT_LIBLLVM_PATH" in os.environ)
    """)
    assert out.split() == ["[]", "False"], out


def test_missing_mitsuba_names_the_extra():
    out = run("""
        import sys
        sys.modules["mitsuba"] = None  # import mitsuba raises ImportError, as where it is not installed
        sys.modules["drjit"] = None
        import mcstat.mitsuba as mm
        for call in (lambda: mm.check_bsdf({"type": "diffuse"}, (0, 0, 1)), mm.pick_variant):
            try:
                call()
            except ImportError as e:
                print(e)
    """)
    lines = out.strip().splitlines()
    assert len(lines) == 2 and all("pip install 'mcstat[mitsuba]'" in x for x in lines), out
