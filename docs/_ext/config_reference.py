"""Sphinx extension: the workflow's configuration reference, generated from ``workflow/schemas/*.schema.yaml``.

At every build (``config-inited``) each schema is walked (local ``$ref`` and ``allOf`` resolved) and written as
``docs/generated/<schema>.md``: one table per top-level key and per study, a row per setting with its type,
default, allowed values and description (units in brackets, as the schema states them). The workflow page includes
it, so the reference cannot drift from the schema that ``snakemake`` validates against.
"""

from __future__ import annotations

from pathlib import Path

import yaml

BOUNDS = (("minimum", ">= {}"), ("exclusiveMinimum", "> {}"), ("maximum", "<= {}"), ("exclusiveMaximum", "< {}"))


def resolve(node: dict, root: dict) -> dict:
    """``node`` with its local ``$ref`` and ``allOf`` merged in (the node's own keys win)."""
    node = dict(node)
    while "$ref" in node:
        ref = node.pop("$ref")
        target = root
        for part in ref.lstrip("#/").split("/"):
            target = target[part]
        node = {**target, **node}
    for extra in node.pop("allOf", []):
        extra = resolve(extra, root)
        merged = {**extra.get("properties", {}), **node.get("properties", {})}
        node = {**extra, **node}
        if merged:
            node["properties"] = merged
    return node


def describe(node: dict, root: dict) -> tuple[str, str]:
    """Type and constraints of a setting, as text."""
    kind = node.get("type", "object" if "properties" in node else "")
    kind = " or ".join(kind) if isinstance(kind, list) else kind
    rules = [rule.format(node[key]) for key, rule in BOUNDS if key in node]
    if "enum" in node:
        rules.append("one of " + ", ".join(f"`{v}`" for v in node["enum"]))
    if kind == "array" and "items" in node:
        item_kind, item_rules = describe(resolve(node["items"], root), root)
        kind = f"list of {item_kind}"
        rules += [f"each {r}" for r in item_rules.split("; ") if r]
        if node.get("minItems"):
            rules.append(f"at least {node['minItems']} item(s)")
    return kind, "; ".join(rules)


def cell(text) -> str:
    return str(text).replace("|", "\\|").replace("\n", " ")


def rows(node: dict, root: dict, path: str, required: set) -> list[str]:
    node = resolve(node, root)
    out = []
    kind, rules = describe(node, root)
    default = f"`{node['default']}`" if "default" in node else ("required" if path.split(".")[-1] in required else "")
    if path:
        description = cell(node.get("description", ""))
        out.append(f"| `{path}` | {cell(kind)} | {cell(default)} | {cell(rules)} | {description} |")
    own_required = set(node.get("required", []))
    for name, child in node.get("properties", {}).items():
        out += rows(child, root, f"{path}.{name}" if path else name, own_required)
    extra = node.get("additionalProperties")
    if isinstance(extra, dict) and extra:
        out += rows(extra, root, f"{path}.<name>", set())
    return out


HEADER = ["| setting | type | default | allowed | description |", "| --- | --- | --- | --- | --- |"]


def reference(schema: dict) -> str:
    lines = [f"{schema.get('description', '')}.", "",
             "Generated from the schema at build time; `required` marks settings without a default.", ""]
    for key, node in schema["properties"].items():
        node = resolve(node, schema)
        if key == "studies":
            continue
        lines += [f"### `{key}`", "", *HEADER, *rows(node, schema, key, set(schema.get("required", []))), ""]
    studies = resolve(schema["properties"]["studies"], schema)
    lines += ["### `studies`", "",
              "Each study has a `title`, study-level `constants`, and a `quick` and a `paper` block, each with its "
              "own `constants` (overriding the study's) and the `grid` of swept parameters (every combination is "
              "solved; `seed` repeats it over surfaces).", ""]
    for name, node in studies.get("properties", {}).items():
        lines += [f"#### `studies.{name}`", "", *HEADER, *rows(node, schema, f"studies.{name}", set()), ""]
    return "\n".join(lines) + "\n"


def write_reference(app, config=None) -> None:
    schemas = sorted((Path(app.srcdir).parent / "workflow" / "schemas").glob("*.schema.yaml"))
    folder = Path(app.srcdir) / "generated"
    folder.mkdir(exist_ok=True)
    for path in schemas:
        text = reference(yaml.safe_load(path.read_text()))
        target = folder / (path.name.removesuffix(".schema.yaml") + ".md")
        if not target.exists() or target.read_text() != text:
            target.write_text(text)


def setup(app):
    app.connect("config-inited", write_reference)
    return {"parallel_read_safe": True, "version": "1"}
