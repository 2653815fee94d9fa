"""Runs the ``mcstat`` command in-process for the image-test tests: the exit
status, stdout and stderr of ``mcstat_app.cli.main`` on argv (each item
str()'d; an argparse exit becomes its status, 2 when it carries a message)."""
import contextlib
import io

from mcstat_app.cli import main


def run_cli(*argv):
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            code = main([str(a) for a in argv])
        except SystemExit as e:
            code = e.code if isinstance(e.code, int) else 2
    return code, out.getvalue(), err.getvalue()
