# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""mcstat_app: the ``mcstat`` command, an application of the library ``mcstat``.

The library (``bindings/python/mcstat``) wraps libmcstat and libmcest and
never imports this package; this package uses only the library's public
API.

==============  ================================================================
cli             the ``mcstat`` command: argument parsing, one function per command
samples         sample files for ``mcstat test`` (.npy, .csv, .tsv, .txt)
image           ``mcstat image-test``: image readers, the significance map (PNG)
reproduce       ``mcstat reproduce``: the paper's case studies; the table of
                studies is ``reproduce/studies.py``
==============  ================================================================

A new command is a function ``_name(args) -> int`` and its sub-parser in
``cli.build_parser``.
"""
