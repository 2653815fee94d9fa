# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""The ``mcstat`` command's exit statuses, and the errors that map to them.

Every failure reaches the user as one line on stderr saying what to do,
with a status that tells its kind apart (``mcstat --help`` lists them):

======  =====================================================================
status  meaning
======  =====================================================================
0       success
1       H0 rejected, with ``--fail-on-reject`` (``image-test``: the verdict
        "different")
2       bad command line: an unknown option, a missing or invalid argument
3       bad input: a file missing, unreadable, corrupt or of the wrong
        format (scene, samples, images), or data a test cannot use
4       a Python package is missing (an extra of mcstat): the line says what
        to ``pip install``
5       an output file or folder cannot be written
6       ``image-test --fail-on-reject``: the verdict is "inconclusive":
        nothing could be tested, or the pass could hide a bias larger
        than ``--max-detectable-bias`` / ``--max-relative-detectable-bias``
        (1 is "different", 0 "equal")
70      an internal error (a bug; ``MCSTAT_TRACEBACK=1`` shows the traceback)
130     interrupted (Ctrl-C)
141     stdout closed early (a broken pipe, e.g. ``| head -1``), as a
        program killed by SIGPIPE reports it to the shell
======  =====================================================================
"""
from __future__ import annotations

import importlib
from typing import Any, Type

EXIT_OK = 0
EXIT_REJECTED = 1
EXIT_USAGE = 2
EXIT_INPUT = 3
EXIT_MISSING_PACKAGE = 4
EXIT_OUTPUT = 5
EXIT_INCONCLUSIVE = 6
EXIT_INTERNAL = 70
EXIT_INTERRUPTED = 130
EXIT_BROKEN_PIPE = 141

EXIT_STATUS_HELP = """exit status:
  0    success
  1    H0 rejected (with --fail-on-reject)
  2    bad command line (an unknown option, a missing or invalid argument)
  3    bad input: a file missing, unreadable, corrupt or of the wrong format; data a test cannot use
  4    a Python package is missing: the message says what to pip install
  5    an output file or folder cannot be written
  6    image-test --fail-on-reject: inconclusive (nothing tested, or the pass could hide a bias above
       --max-detectable-bias / --max-relative-detectable-bias); 1 there is "different", 0 "equal"
  70   internal error (a bug: please report it; MCSTAT_TRACEBACK=1 shows the traceback)
  130  interrupted
  141  stdout closed early (broken pipe)"""

# import name -> (PyPI name, the extra of mcstat that brings it)
PACKAGES = {
    "matplotlib": ("matplotlib", "report"),
    "tqdm": ("tqdm", "report"),
    "PIL": ("pillow", "image"),
    "OpenEXR": ("OpenEXR", "image"),
    "scipy": ("scipy", None),
    "numpy": ("numpy", None),
    "tomli": ("tomli", None),
}


class UsageError(Exception):
    """A bad combination of command-line arguments (status 2)."""


class OutputError(Exception):
    """An output that cannot be written (status 5)."""


class MissingPackageError(ImportError):
    """A Python package that a command needs is not installed (status 4).

    The message is one line: what needs it and what to ``pip install``."""

    def __init__(self, module: str, purpose: str, reason: str = "") -> None:
        top = module.split(".")[0]
        dist, extra = PACKAGES.get(top, (top, None))
        how = f"pip install 'mcstat[{extra}]' (or: pip install {dist})" if extra else f"pip install {dist}"
        state = f"which cannot be imported ({reason})" if reason else "which is not installed"
        super().__init__(f"{purpose} needs the Python package {dist}, {state}: {how}", name=top)
        self.package, self.extra = dist, extra


def require(module: str, purpose: str, error: Type[MissingPackageError] = MissingPackageError) -> Any:
    """``import module``, or `error` (a MissingPackageError) naming what to install."""
    try:
        return importlib.import_module(module)
    except ImportError as e:
        # installed but broken (e.g. a shared library it needs): say why
        reason = "" if isinstance(e, ModuleNotFoundError) and e.name == module.split(".")[0] else str(e)
        raise error(module, purpose, reason) from e
