#!/usr/bin/env python3
"""Doxygen INPUT_FILTER for mcstat's C headers (tools/docs/Doxyfile).

The headers document in plain C comments, laid out as text (aligned
columns, formulas, tables), not in Doxygen's markup.  This filter hands them
to Doxygen as documentation without rewriting them: a comment on lines of its
own (and the comments on the lines right after it) becomes a doc block shown
verbatim, attached to the declaration that follows; a comment after code on
the same line (a struct member, an enumerator) becomes a trailing doc
comment, its markup characters escaped; the file's first comment documents
the file.  Comments inside function bodies stay plain.  Line numbers are
kept, so Doxygen's locations are the header's.

usage: doxygen_filter.py FILE   (writes the filtered file to stdout)
"""
import os
import re
import sys

ESCAPE = re.compile(r'([\\@<>&#%$"`~|])')


def comments(text):
    """(start, end, in_body) of each /* */ comment outside string and char
    literals; in_body is True inside a function body (a brace that follows
    a closing parenthesis)."""
    i, n = 0, len(text)
    out = []
    depth_body = 0  # > 0 inside a function body
    stack = []  # for each open brace: was it a function body?
    last_code = ""
    while i < n:
        c = text[i]
        if text.startswith("/*", i):
            j = text.index("*/", i + 2) + 2
            out.append((i, j, depth_body > 0))
            i = j
        elif text.startswith("//", i):
            i = text.find("\n", i)
            i = n if i < 0 else i
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            i = j + 1
            last_code = c
        elif c == "{":
            body = last_code == ")"
            stack.append(body)
            depth_body += body
            last_code = c
            i += 1
        elif c == "}":
            if stack:
                depth_body -= stack.pop()
            last_code = c
            i += 1
        else:
            if not c.isspace():
                last_code = c
            i += 1
    return out


def body_lines(comment):
    """The text lines of a comment, delimiters and leading ' * ' removed."""
    inner = comment[2:-2]
    lines = inner.split("\n")
    res = []
    for k, line in enumerate(lines):
        if k > 0:
            line = re.sub(r"^\s*\* ?", "", line, count=1) if re.match(r"^\s*\*(?!/)", line) else line.strip()
        res.append(line.rstrip())
    return res


def main(path):
    text = open(path, encoding="utf-8").read()
    spans = comments(text)
    out = []
    pos = 0
    first = True
    k = 0
    while k < len(spans):
        start, end, in_body = spans[k]
        line_start = text.rfind("\n", 0, start) + 1
        leading = text[line_start:start]
        if in_body:
            k += 1
            continue
        if leading.strip():  # after code on its line: a trailing comment
            body = " ".join(part.strip() for part in body_lines(text[start:end]))
            out.append(text[pos:start])
            newlines = text.count("\n", start, end)
            out.append("/**< " + ESCAPE.sub(r"\\\1", body) + "\n" * newlines + " */")
            pos = end
            k += 1
            continue
        # a group: this comment and those starting on the very next lines
        group = [(start, end)]
        while k + 1 < len(spans):
            s2, e2, b2 = spans[k + 1]
            between = text[group[-1][1]:s2]
            if b2 or between.count("\n") != 1 or between.strip():
                break
            group.append((s2, e2))
            k += 1
        lines = []
        for s, e in group:
            lines.extend(body_lines(text[s:e]))
        head = "/** \\file %s " % os.path.basename(path) if first else "/** "
        first = False
        # the verbatim opens and closes on the first and last text lines, so
        # the block has the group's line count
        block = head + "\\verbatim " + "\n".join(lines) + " \\endverbatim */"
        n_src = text.count("\n", group[0][0], group[-1][1])
        assert block.count("\n") == n_src, (path, text[group[0][0]:group[-1][1]][:80])
        out.append(text[pos:group[0][0]])
        out.append(block)
        pos = group[-1][1]
        k += 1
    out.append(text[pos:])
    sys.stdout.write("".join(out))


if __name__ == "__main__":
    main(sys.argv[1])
