# Sphinx configuration of the Python API reference (make docs-python): the
# installed mcstat package's docstrings through autodoc and napoleon (NumPy
# style).  make docs runs sphinx-build -W (warnings are errors) with the
# .venv's Python, where `make python` installed the package.
import re

project = "mcstat"
author = "the mcstat developers"
extensions = ["sphinx.ext.autodoc", "sphinx.ext.napoleon"]
autodoc_default_options = {"members": True, "show-inheritance": True}
autodoc_member_order = "bysource"
# Attributes sections as fields of their class: autodoc documents the
# members of the named tuples already, and a second description of each
# would be a duplicate.
napoleon_use_ivar = True
# The words of a NumPy-style type ("ndarray, shape (n,)") become references;
# "n" and "mean" then match members of both Moments and MomentsArray, and
# Sphinx warns that the reference is ambiguous.  Those words were never meant
# as references: only this ambiguity warning is off (no other is).
suppress_warnings = ["ref.python"]
html_theme = "alabaster"


def _drop_readable_signature(app, what, name, obj, options, lines):
    """The extension's functions (pybind11) carry two signatures: pybind11's
    typed one, which autodoc takes as the signature, and below it, for
    help(), the readable one of the docstring's first line, which would
    otherwise be parsed as text (its ``*`` as emphasis)."""
    short = name.rsplit(".", 1)[-1]
    pattern = re.compile(r"^%s\(.*\)$" % re.escape(short))
    for i, line in enumerate(lines[:2]):
        if pattern.match(line):
            del lines[i]
            if i < len(lines) and not lines[i].strip():
                del lines[i]
            break


def setup(app):
    app.connect("autodoc-process-docstring", _drop_readable_signature)
