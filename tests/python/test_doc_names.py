"""The documents name only what exists: every mcstat_* / MCSTAT_* name in the
tree's Markdown files is declared by a public header (mcstat.h and its
families mcstat/*.h, mcstat_check.h, mcstat_testing.h, mcstat_pbrt.h, mcest.h), or is one of the build options,
environment variables and programs listed here, each of which must itself
appear in the tree's sources.  A name the header keeps only as deprecated
(its last section) may be named by the CHANGELOG alone.  A prefix written
as a family (`mcstat_pixels_*`, `mcstat_seq_push_`) is not a name.  Reads
the source tree, not the installed package."""
import pathlib
import re
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
# mcstat.h, then its families (mcstat/*.h), then the other public headers
FAMILIES = sorted(str(p.relative_to(ROOT)) for p in (ROOT / "libmcstat/include/mcstat").glob("*.h"))
HEADERS = ["libmcstat/include/mcstat.h", *FAMILIES, "libmcstat/include/mcstat_check.h",
           "libmcstat/include/mcstat_testing.h", "libmcstat/include/mcstat_pbrt.h",
           "estimators/include/mcest.h"]
DEPRECATED_MARK = re.compile(r"^/\* \d+\. Deprecated names\.", re.M)  # mcstat/deprecated.h's section
NAME = re.compile(r"\b(?:mcstat|MCSTAT)_\w*")

# Names that are not C API but are documented: CMake options and targets,
# environment variables, programs and modules.  Each must appear in a source.
NOT_API = {
    "MCSTAT_BUILD_BENCH", "MCSTAT_BUILD_ESTIMATORS", "MCSTAT_BUILD_EXAMPLES", "MCSTAT_BUILD_TESTS",
    "MCSTAT_INSTALL", "MCSTAT_FUZZ", "MCSTAT_SOURCES", "MCSTAT_TESTS", "mcstat_static",
    "MCSTAT_NUM_THREADS", "MCSTAT_TEST_SCALE", "MCSTAT_TEST_THREADS", "MCSTAT_TEST_THREADS_REPS",
    "MCSTAT_TRACEBACK", "MCSTAT_DEMO_PLANT", "MCSTAT_MITSUBA_VARIANT", "MCSTAT_FUZZ_VERBOSE",
    "mcstat_app", "mcstat_ctypes",
    "mcstat_name",  # CONTRIBUTING's placeholder in an exemption line's format
    "mcstat_tests",  # the pytest plugin's ini option
}


def tracked():
    out = subprocess.run(["git", "ls-files"], cwd=ROOT, capture_output=True, text=True)
    if out.returncode != 0:
        pytest.skip("not a git checkout")
    return [ROOT / p for p in out.stdout.split()]


def header_names():
    current, deprecated = set(), set()
    for h in HEADERS:
        text = (ROOT / h).read_text()
        found = DEPRECATED_MARK.search(text)
        cut = found.start() if found else -1
        head, tail = (text, "") if cut < 0 else (text[:cut], text[cut:])
        current |= set(NAME.findall(head))
        deprecated |= set(NAME.findall(tail))
    return current, deprecated - current


def names_in(path):
    """(line number, name) of each whole name in a document"""
    for k, line in enumerate(path.read_text().splitlines(), 1):
        for m in NAME.finditer(line):
            name = m.group(0)
            after = line[m.end():m.end() + 1]
            if name.endswith("_") or after in ("*", "<", "{"):
                continue  # a family of names, not one
            yield k, name


def test_documents_name_only_declared_symbols():
    files = tracked()
    docs = [p for p in files if p.suffix == ".md"]
    assert any(p.name == "README.md" for p in docs)
    current, deprecated = header_names()
    internal = set()
    for p in files:
        if p.suffix in (".c", ".h") and "libmcstat/src" in str(p):
            internal |= set(re.findall(r"\bmcstat__\w+", p.read_text()))
    bad = []
    for p in docs:
        rel = p.relative_to(ROOT)
        for k, name in names_in(p):
            if name in current or name in NOT_API:
                continue
            if name.startswith("mcstat__") and name in internal:
                continue  # the library's hidden helpers, named by the fuzz notes
            if name in deprecated:
                if rel.name != "CHANGELOG.md":
                    bad.append(f"{rel}:{k}: {name} is deprecated (mcstat.h, section 'Deprecated names')")
                continue
            bad.append(f"{rel}:{k}: {name} is declared by no public header")
    assert not bad, "\n".join(bad)


def test_listed_names_exist_in_the_sources():
    sources = [p for p in tracked() if p.suffix not in (".md",) and p.is_file() and p.stat().st_size < 2_000_000]
    text = []
    for p in sources:
        try:
            text.append(p.read_text())
        except (UnicodeDecodeError, OSError):
            continue
    blob = "\n".join(text)
    missing = sorted(n for n in NOT_API if n != "mcstat_name" and not re.search(r"\b" + n + r"\b", blob))
    assert not missing, f"listed in NOT_API but in no source: {missing}"


def test_readme_is_a_front_page():
    """The README says what mcstat is, how to install it and the quickstarts
    (seven programs, each built and run as written by make quickstart-test:
    the cap leaves them room and nothing else); the reference is in docs/ (a
    guide per concern), which it links."""
    readme = (ROOT / "README.md").read_text()
    assert len(readme.splitlines()) <= 330, "README.md over 330 lines: move the detail into docs/"
    index = (ROOT / "docs" / "README.md").read_text()
    for guide in sorted((ROOT / "docs").glob("*.md")):
        if guide.name != "README.md":
            assert guide.name in index, f"docs/README.md does not list {guide.name}"


SECTION_NUMBER = re.compile(r"mcstat\.h`?'?(?:,|'s)? (?:experimental )?sections? \d")
HEADER_SECTION_NUMBER = re.compile(r"(?<!paper's )\bsections? \d+b?\b(?!\.\d)")


def test_header_sections_are_named_by_title():
    """Other files name mcstat.h's sections by title, never by number (the
    numbers change when a section moves); inside the public headers, a
    number is a section of the paper ("the paper's section 3", "2.1")."""
    bad = []
    for p in tracked():
        if p.suffix not in (".md", ".py", ".c", ".h", ".rs", ".go", ".cpp", ".hpp") or p.name == "CHANGELOG.md":
            continue
        rel = str(p.relative_to(ROOT))
        for k, line in enumerate(p.read_text().splitlines(), 1):
            if SECTION_NUMBER.search(line):
                bad.append(f"{rel}:{k}: {line.strip()}")
            elif rel.startswith("libmcstat/include/") and HEADER_SECTION_NUMBER.search(line) and not re.match(r"/\* \d+b?\. ", line):
                bad.append(f"{rel}:{k}: {line.strip()}")
    assert not bad, "sections named by number:\n" + "\n".join(bad)


SECTION = re.compile(r"^/\* (\d+)\. ([^.(]+?)[.,]", re.M)


def test_headers_name_sections_by_title_not_number():
    """Sections are renumbered as the header grows: a cross-reference names
    a section by its title.  Caught: "section 11" (but not the paper's
    "section 2.1" or "the paper's section 3") and a title followed by a
    parenthesised number, "Equivalence (6)"."""
    text = "".join((ROOT / h).read_text() for h in FAMILIES)
    titles = [t.strip() for _, t in SECTION.findall(text)]
    assert len(titles) >= 10, titles
    bad = []
    for h in HEADERS:
        for k, line in enumerate((ROOT / h).read_text().splitlines(), 1):
            for m in re.finditer(r"\bsections? (\d+)\b(?!\.\d)", line):
                if "paper" not in line[:m.start()]:
                    bad.append(f"{h}:{k}: {line.strip()}")
            for t in titles:
                first = t.split(",")[0].split()[0]
                if re.search(rf"\b{re.escape(first)}\w*(?: \w+){{0,3}} \(\d{{1,2}}\)", line, re.I):
                    bad.append(f"{h}:{k}: {line.strip()}")
    assert not bad, "\n".join(bad)
