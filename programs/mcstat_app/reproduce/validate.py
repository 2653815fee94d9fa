# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""A small JSON Schema validator: the subset that schema.json uses.

The scene schema (``schema.json`` beside this file, also shipped as
``examples/scenes/schema.json``) is the single source of the scene format:
field names, types, ranges and defaults.  This module checks a parsed
document against it, fills in the defaults, and names every problem by its
path, e.g. ``scene.brdfs[1].alpha_x: expected a number > 0, got -2``.

Supported keywords: ``type`` (object, array, number, integer, string,
boolean), ``properties``, ``required``, ``additionalProperties: false``,
``default``, ``items``, ``minItems``, ``maxItems``, ``uniqueItems``,
``minimum``, ``maximum``, ``exclusiveMinimum``, ``exclusiveMaximum``,
``enum``, ``const``, ``minLength``, ``$ref`` (to ``#/$defs/...``) and
``oneOf`` where the branches can be told apart without trying them all:
by their ``type``, or by a ``const`` property they all have (a
discriminator such as ``model``).  Anything else in the schema is a
programming error and raises at load time (so the schema cannot silently
say more than is checked).
"""
from __future__ import annotations

import copy
import math
from typing import Any, Dict, List, Optional

_KNOWN = {
    "$schema", "$id", "$defs", "$ref", "$comment", "title", "description", "examples", "type", "properties",
    "required", "additionalProperties", "default", "items", "minItems", "maxItems", "uniqueItems", "minimum",
    "maximum", "exclusiveMinimum", "exclusiveMaximum", "enum", "const", "oneOf", "minLength",
}
_TYPE_WORDS = {
    "object": "an object (a table)",
    "array": "a list",
    "number": "a number",
    "integer": "an integer",
    "string": "a string",
    "boolean": "true or false",
}


def check_schema(schema: Dict[str, Any]) -> None:
    """Raise ValueError if the schema uses a keyword this validator ignores."""

    def walk(node: Any, where: str) -> None:
        if isinstance(node, dict):
            unknown = set(node) - _KNOWN
            if unknown:
                raise ValueError(f"schema {where}: unsupported keywords {sorted(unknown)}")
            for key in ("properties", "$defs"):
                for name, sub in node.get(key, {}).items():
                    walk(sub, f"{where}.{key}.{name}")
            if "items" in node:
                walk(node["items"], where + ".items")
            for i, sub in enumerate(node.get("oneOf", [])):
                walk(sub, f"{where}.oneOf[{i}]")

    walk(schema, "#")


def show(value: Any) -> str:
    """A value as the user wrote it (JSON-like), shortened."""
    if isinstance(value, bool):
        text = "true" if value else "false"
    elif isinstance(value, str):
        text = repr(value)
    elif isinstance(value, float) and value.is_integer() and abs(value) < 1e16:
        text = repr(value)
    elif isinstance(value, dict):
        text = "an object with fields " + ", ".join(map(str, value)) if value else "an empty object"
    elif value is None:
        text = "null"
    else:
        text = repr(value)
    return text if len(text) <= 80 else text[:77] + "..."


def _fmt(x: float) -> str:
    return f"{x:g}"


def _is_type(value: Any, t: str) -> bool:
    if t == "object":
        return isinstance(value, dict)
    if t == "array":
        return isinstance(value, list)
    if t == "string":
        return isinstance(value, str)
    if t == "boolean":
        return isinstance(value, bool)
    if t == "integer":
        return (isinstance(value, int) and not isinstance(value, bool)) or (
            isinstance(value, float) and math.isfinite(value) and value.is_integer())
    if t == "number":
        return isinstance(value, (int, float)) and not isinstance(value, bool)
    raise ValueError(f"schema: unknown type {t!r}")


def _expected(node: Dict[str, Any]) -> str:
    """'a number > 0 and <= 10', 'one of "U", "C"', ... from the keywords."""
    if "enum" in node:
        return "one of " + ", ".join(show(v) for v in node["enum"])
    if "const" in node:
        return show(node["const"])
    t = node.get("type")
    words = _TYPE_WORDS.get(t, "a value") if isinstance(t, str) else " or ".join(_TYPE_WORDS[x] for x in t)
    bounds = []
    if "exclusiveMinimum" in node:
        bounds.append(f"> {_fmt(node['exclusiveMinimum'])}")
    if "minimum" in node:
        bounds.append(f">= {_fmt(node['minimum'])}")
    if "exclusiveMaximum" in node:
        bounds.append(f"< {_fmt(node['exclusiveMaximum'])}")
    if "maximum" in node:
        bounds.append(f"<= {_fmt(node['maximum'])}")
    if t == "array":
        lo, hi = node.get("minItems"), node.get("maxItems")
        if lo is not None and lo == hi:
            words = f"a list of {lo}"
        elif lo:
            words = f"a list of at least {lo}"
        elif hi is not None:
            words = f"a list of at most {hi}"
        item = node.get("items")
        if isinstance(item, dict) and "type" in item and lo is not None and lo == hi:
            words += " " + {"number": "numbers", "integer": "integers", "string": "strings"}.get(
                item["type"] if isinstance(item["type"], str) else "", "items")
    if bounds:
        words += " " + " and ".join(bounds)
    return words


class Validator:
    """Checks documents against one schema; collects every error."""

    def __init__(self, schema: Dict[str, Any]) -> None:
        check_schema(schema)
        self.schema = schema

    def _resolve(self, node: Dict[str, Any]) -> Dict[str, Any]:
        while "$ref" in node:
            ref = node["$ref"]
            if not ref.startswith("#/$defs/"):
                raise ValueError(f"schema: unsupported $ref {ref!r}")
            node = self.schema["$defs"][ref[len("#/$defs/"):]]
        return node

    def validate(self, doc: Any, root: str = "scene") -> tuple:
        """(the document with defaults filled in, [error lines])."""
        errors: List[str] = []
        out = self._check(copy.deepcopy(doc), self.schema, root, errors)
        return out, errors

    # -- the walk ------------------------------------------------------------
    def _check(self, value: Any, node: Dict[str, Any], path: str, errors: List[str]) -> Any:
        node = self._resolve(node)
        if "oneOf" in node:
            branch = self._pick(value, node, path, errors)
            if branch is None:
                return value
            node = branch
        t = node.get("type")
        if t is not None:
            types = [t] if isinstance(t, str) else t
            if not any(_is_type(value, x) for x in types):
                errors.append(f"{path}: expected {_expected(node)}, got {show(value)}")
                return value
            if "integer" in types and isinstance(value, float):
                value = int(value)
        if isinstance(value, float) and not math.isfinite(value):
            errors.append(f"{path}: expected {_expected(node)}, got {show(value)}")
            return value
        if "const" in node and value != node["const"]:
            errors.append(f"{path}: expected {show(node['const'])}, got {show(value)}")
        if "enum" in node and value not in node["enum"]:
            errors.append(f"{path}: expected {_expected(node)}, got {show(value)}")
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            ok = True
            ok &= "minimum" not in node or value >= node["minimum"]
            ok &= "maximum" not in node or value <= node["maximum"]
            ok &= "exclusiveMinimum" not in node or value > node["exclusiveMinimum"]
            ok &= "exclusiveMaximum" not in node or value < node["exclusiveMaximum"]
            if not ok:
                errors.append(f"{path}: expected {_expected(node)}, got {show(value)}")
        if isinstance(value, str) and len(value) < node.get("minLength", 0):
            errors.append(f"{path}: expected a string of at least {node['minLength']} characters, got {show(value)}")
        if isinstance(value, list):
            n = len(value)
            if n < node.get("minItems", 0) or ("maxItems" in node and n > node["maxItems"]):
                errors.append(f"{path}: expected {_expected(node)}, got {n} item{'s' if n != 1 else ''}")
            if "items" in node:
                value = [self._check(v, node["items"], f"{path}[{i}]", errors) for i, v in enumerate(value)]
            if node.get("uniqueItems"):
                seen = []
                for i, v in enumerate(value):
                    if v in seen:
                        errors.append(f"{path}[{i}]: {show(v)} appears twice; expected each at most once")
                    seen.append(v)
        if isinstance(value, dict) and node.get("type") == "object":
            props = node.get("properties", {})
            for name in node.get("required", []):
                if name not in value:
                    sub = self._resolve(props.get(name, {}))
                    errors.append(f"{path}.{name}: required field missing; expected {_expected(sub)}")
            if node.get("additionalProperties", True) is False:
                for name in value:
                    if name not in props:
                        errors.append(f"{path}.{name}: unknown field; expected one of " + ", ".join(props))
            for name, sub in props.items():
                if name in value:
                    value[name] = self._check(value[name], sub, f"{path}.{name}", errors)
                else:
                    subr = self._resolve(sub)
                    if "default" in subr:
                        value[name] = self._check(copy.deepcopy(subr["default"]), subr, f"{path}.{name}", errors)
        return value

    def _pick(self, value: Any, node: Dict[str, Any], path: str, errors: List[str]) -> Optional[Dict[str, Any]]:
        branches = [self._resolve(b) for b in node["oneOf"]]
        types = [b.get("type") for b in branches]
        if all(isinstance(t, str) for t in types) and len(set(types)) == len(types):
            for b in branches:
                if _is_type(value, b["type"]):
                    return b
            errors.append(f"{path}: expected " + " or ".join(_expected(b) for b in branches) + f", got {show(value)}")
            return None
        # objects told apart by a const property they all have
        keys = set.intersection(*[
            {k for k, s in b.get("properties", {}).items() if "const" in self._resolve(s)} for b in branches])
        if len(keys) != 1:
            raise ValueError(f"schema at {path}: oneOf branches need distinct types or one const discriminator")
        key = keys.pop()
        consts = [self._resolve(b["properties"][key])["const"] for b in branches]
        if not isinstance(value, dict):
            errors.append(f"{path}: expected an object (a table), got {show(value)}")
            return None
        if key not in value:
            errors.append(f"{path}.{key}: required field missing; expected one of " + ", ".join(map(show, consts)))
            return None
        for b, c in zip(branches, consts):
            if value[key] == c:
                return b
        errors.append(f"{path}.{key}: expected one of " + ", ".join(map(show, consts)) + f", got {show(value[key])}")
        return None
