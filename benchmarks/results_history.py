"""``RESULTS.md`` keeps the latest run of each benchmark; the runs it superseded live in ``history/<benchmark>.jsonl``.

One JSON record a line, oldest first: ``benchmark``, ``heading`` (the section's title; ``parent_heading`` when it
was a subsection), ``date``, ``commit`` and ``command`` where the text states them (else null), ``machine``,
``tables`` (each markdown table that parses: ``header`` and ``rows``, a dict per row keyed by the header),
``text`` (the section's markdown, verbatim, heading included) and, for a subsection, ``parent_text`` (its
section's heading and introduction).

When a benchmark is run again, archive its section before pasting the new one::

    python -m benchmarks.results_history archive bench_solver

moves the ``## bench_solver`` section of ``RESULTS.md`` to the end of ``history/bench_solver.jsonl``.
"""

from __future__ import annotations

import argparse
import json
import re
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
RESULTS = HERE / "RESULTS.md"
HISTORY = HERE / "history"
DEFAULT_MACHINE = "the shared 2-core virtual machine (RESULTS.md: absolute times noisy, ratios within one run)"

_DATE = re.compile(r"\b20\d\d-\d\d-\d\d\b")
_COMMIT = re.compile(r"(?:revision|commit|git|contactlib|after|at|base|branch \S+ =|\()\s+`?([0-9a-f]{7,40})\b|"
                     r"\(([0-9a-f]{7,40}), 20\d\d-", re.I)
_COMMANDS = (re.compile(r"`((?:[A-Z_]+=\S+\s+)*python[^`]*bench_[^`]*)`"), re.compile(r"`(bench_[a-z_]+\.py [^`]*)`"))
_MACHINE = re.compile(r"(otherwise idle machine|idle machine|shared 2-core machine|2 cores shared with other[^,;)]*|"
                      r"2 vCPUs[^,;)]*|shared 2-core[^,;)]*|loaded to a load average of [0-9.\-]+ on 2 cores)", re.I)
_HEADER_LINES = 15  # where a run states its date, commit and machine: the section's first lines


def heading_lines(markdown: str) -> list[str]:
    """The heading lines of ``markdown`` (``#`` to ``######``), fenced code left out."""
    out, fenced = [], False
    for line in markdown.splitlines():
        if line.startswith("```"):
            fenced = not fenced
        elif not fenced and re.match(r"#{1,6} ", line):
            out.append(line.rstrip())
    return out


def split_sections(markdown: str, level: int = 2) -> list[tuple[str, str]]:
    """``(heading line, text)`` of each section at ``level`` (the text from its heading to the next heading of that
    level; a pasted ``# `` output line is text); the lines before the first such heading come first, with an empty
    heading."""
    sections, heading, lines, fenced = [], "", [], False
    for line in markdown.splitlines(keepends=True):
        if line.startswith("```"):
            fenced = not fenced
        match = None if fenced else re.match(r"(#{1,6}) ", line)
        if match and len(match.group(1)) == level:
            sections.append((heading, "".join(lines)))
            heading, lines = line.rstrip(), []
        lines.append(line)
    sections.append((heading, "".join(lines)))
    return sections


def _cells(line: str) -> list[str]:
    inner = line.strip()
    inner = inner[1:] if inner.startswith("|") else inner
    inner = inner[:-1] if inner.endswith("|") and not inner.endswith("\\|") else inner
    return [c.strip().replace("\\|", "|") for c in re.split(r"(?<!\\)\|", inner)]


def tables(markdown: str) -> list[dict]:
    """Every markdown table of ``markdown`` whose rows all have the header's number of cells."""
    out, block, fenced = [], [], False
    for line in markdown.splitlines() + [""]:
        if line.startswith("```"):
            fenced = not fenced
        if not fenced and line.lstrip().startswith("|"):
            block.append(line)
            continue
        if len(block) >= 2 and re.fullmatch(r"[\s|:\-]+", block[1]):
            header, rows = _cells(block[0]), [_cells(r) for r in block[2:]]
            if all(len(r) == len(header) for r in rows):
                out.append({"header": header, "rows": [dict(zip(header, r)) for r in rows]})
        block = []
    return out


def record(benchmark: str, text: str, *, parent_heading: str | None = None, parent_text: str = "") -> dict:
    """The history record of one section's markdown ``text`` (its heading line first). A subsection keeps its
    section's heading and introduction (``parent_text``), where its date, commit or machine may be stated."""
    heading = text.splitlines()[0].lstrip("#").strip()
    run = re.search(r"^- run: (.*)$", text, re.M)  # a section archived from RESULTS.md names its run there
    heading = run.group(1).strip() if heading == benchmark and run else heading
    head = "\n".join(text.splitlines()[:_HEADER_LINES])
    date, commit, machine = (pattern.search(head) or pattern.search(parent_text) for pattern in (_DATE, _COMMIT,
                                                                                                  _MACHINE))
    command = next((m for m in (pattern.search(text) for pattern in _COMMANDS) if m), None)
    rec = {"benchmark": benchmark, "heading": heading, "parent_heading": parent_heading,
            "date": date.group(0) if date else None, "commit": commit.group(1) or commit.group(2) if commit else None,
            "machine": machine.group(1).strip() if machine else DEFAULT_MACHINE,
            "command": " ".join(command.group(1).split()) if command else None, "tables": tables(text), "text": text}
    if parent_text:
        rec["parent_text"] = parent_text
    return rec


def append(records: list[dict], history: Path = HISTORY) -> None:
    """Append ``records`` to their benchmarks' history files."""
    history.mkdir(exist_ok=True)
    for rec in records:
        with open(history / f"{rec['benchmark']}.jsonl", "a") as f:
            f.write(json.dumps(rec, ensure_ascii=False) + "\n")


def archive(benchmark: str, results: Path = RESULTS, history: Path = HISTORY) -> dict:
    """Move the ``## <benchmark>`` section of ``results`` to its history file; returns the record."""
    sections = split_sections(results.read_text())
    keep, moved = [], None
    for heading, text in sections:
        if heading == f"## {benchmark}":
            moved = text
        else:
            keep.append(text)
    if moved is None:
        raise ValueError(f"benchmark {benchmark!r} has no '## {benchmark}' section in {results}")
    rec = record(benchmark, moved)
    append([rec], history)
    results.write_text("".join(keep))
    return rec


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = ap.add_subparsers(dest="action", required=True)
    sub.add_parser("archive", help="move a benchmark's section of RESULTS.md to its history").add_argument("benchmark")
    args = ap.parse_args(argv)
    rec = archive(args.benchmark)
    print(f"archived '{rec['heading']}' ({rec['date']}, {rec['commit']}) to history/{args.benchmark}.jsonl")
    return 0


if __name__ == "__main__":
    sys.exit(main())
