"""Every command and Python block of the README and of docs/ runs, in a fresh directory.

Fenced ``bash`` blocks hold commands, one per line (``&&`` chains several); each is run in
order in one fresh temporary directory per document, and must exit with 0 (or with the code a
trailing ``# exit code N`` names) and write exactly the files its arguments say it writes.
``pip install`` (the package is installed already), ``pytest`` (this run) and the benchmark
harness (it needs the peers of ``.[bench]``) are not run. Fenced ``python`` blocks run in
order in one namespace per document. ``text`` blocks are output: each is the output of the
first ``groove`` command of the ``bash`` block before it, line by line (a line ending in
``, ...`` is the start of one).
"""

from __future__ import annotations

import re
import shlex
from pathlib import Path

import pytest

from groove_model.cli.common import compliance_from, compliance_label
from groove_model.cli.main import build_parser, main
from groove_model.cli.reproduce import steps
from groove_model.cli.trace import overlay_name
from groove_model.io.export import boundary_file_names

ROOT = Path(__file__).resolve().parents[1]
DOCUMENTS = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
#: Commands that are not run here, and why.
NOT_RUN = {
    "python3 -m pip install": "the package under test is installed already",
    "python3 -m pytest": "this is the test run",
    "python3 benchmarks/run.py": "needs the benchmark peers (.[bench]) and minutes",
}
#: Commands run only with the slow tests (tens of seconds each).
SLOW = ("groove reproduce", "groove compliance")
FENCE = re.compile(r"^```(\w*)\n(.*?)^```", re.MULTILINE | re.DOTALL)


def _blocks(path: Path, language: str) -> list[str]:
    return [body for lang, body in FENCE.findall(path.read_text()) if lang == language]


def _commands(path: Path) -> list[tuple[str, int]]:
    """``(command, expected exit code)`` of every bash line, ``&&`` chains split."""
    out = []
    for block in _blocks(path, "bash"):
        for line in block.splitlines():
            code, _, comment = line.partition(" #")
            match = re.search(r"exit code (\d+)", comment)
            for command in filter(None, (c.strip() for c in code.split("&&"))):
                if command.startswith("#"):
                    continue
                out.append((command, int(match.group(1)) if match else 0))
    return out


def _expected_files(argv: list[str]) -> set[str] | None:
    """The files a ``groove`` command writes, from its arguments (None: not known here)."""
    if not argv or argv[0] in ("--version", "--help", "-h") or "--help" in argv:
        return set()
    args = build_parser().parse_args(argv)
    if args.command == "solve":
        return set()
    if args.command == "trace":
        out = Path(args.out)
        ks = list(dict.fromkeys(args.ks))
        suffix = compliance_label(compliance_from(args))
        files = {str(out / name) for k in ks for name in boundary_file_names(k, suffix)}
        if not args.no_figure:
            stem = args.figure or overlay_name(ks) + suffix
            files |= {str(out / f"{stem}.png"), str(out / f"{stem}.svg")}
        return files
    if args.command in ("plot", "map"):
        target = Path(args.output)
        svg = [target.with_suffix(".svg")] if getattr(args, "svg", False) else []
        return {str(p) for p in [target, *svg]}
    if args.command == "audit":
        return {str(Path(args.out) / n) for n in ("claims.md", "claims.json")} if args.out \
            else set()
    if args.command == "reproduce":
        per_step = [_expected_files(step) for step in steps(Path(args.out))]
        return None if None in per_step else set().union(*per_step)
    return None


def _files(directory: Path) -> dict[str, int]:
    return {str(p.relative_to(directory)): p.stat().st_mtime_ns
            for p in directory.rglob("*") if p.is_file()}


def _run(command: str, expected_code: int, directory: Path, monkeypatch, capsys) -> None:
    """Run one documented command in-process (as the console script would) in ``directory``."""
    argv = shlex.split(command)
    if argv[:3] == ["python3", "-m", "groove_model"]:
        argv = ["groove", *argv[3:]]
    assert argv[0] == "groove", f"a documented command that is not groove: {command}"
    monkeypatch.chdir(directory)
    before = _files(directory)
    try:
        code = main(argv[1:])
    except SystemExit as exc:  # argparse's --help, --version and usage errors
        code = exc.code if isinstance(exc.code, int) else 1
    output = capsys.readouterr()
    assert code == expected_code, f"{command}\n{output.out}\n{output.err}"
    after = _files(directory)
    written = {name for name, mtime in after.items() if before.get(name) != mtime}
    expected = _expected_files(argv[1:])
    if expected is not None:
        assert written == {str(Path(p)) for p in expected}, command
    elif "--out" in argv:
        assert written, f"{command} wrote nothing"


def _run_commands(path: Path, tmp_path: Path, slow: bool, monkeypatch, capsys) -> int:
    ran = 0
    for command, code in _commands(path):
        if any(command.startswith(prefix) for prefix in NOT_RUN):
            continue
        if command.startswith(SLOW) != slow:
            continue
        _run(command, code, tmp_path, monkeypatch, capsys)
        ran += 1
    return ran


@pytest.mark.parametrize("path", DOCUMENTS, ids=lambda p: p.name)
def test_documented_commands(path, tmp_path, monkeypatch, capsys):
    _run_commands(path, tmp_path, False, monkeypatch, capsys)


@pytest.mark.slow
@pytest.mark.parametrize("path", DOCUMENTS, ids=lambda p: p.name)
def test_documented_slow_commands(path, tmp_path, monkeypatch, capsys):
    _run_commands(path, tmp_path, True, monkeypatch, capsys)


@pytest.mark.parametrize("path", DOCUMENTS, ids=lambda p: p.name)
def test_python_blocks(path, tmp_path, monkeypatch, capsys):
    import matplotlib

    matplotlib.use("Agg")
    monkeypatch.chdir(tmp_path)
    namespace: dict = {"__name__": "__doc_example__"}
    for i, block in enumerate(_blocks(path, "python")):
        exec(compile(block, f"{path.name}[python block {i + 1}]", "exec"), namespace)


def _samples(path: Path) -> list[tuple[str, list[str]]]:
    """``(command, lines)`` of every ``text`` block: the first ``groove`` command of the ``bash``
    block before it, and the block's lines."""
    samples, command = [], None
    for lang, body in FENCE.findall(path.read_text()):
        if lang == "bash":
            command = next((line.partition(" #")[0].strip() for line in body.splitlines()
                            if line.startswith("groove ")), None)
        elif lang == "text" and command is not None:
            samples.append((command, body.splitlines()))
    return samples


@pytest.mark.parametrize("path", DOCUMENTS, ids=lambda p: p.name)
def test_output_samples_are_the_programs_output(path, tmp_path, monkeypatch, capsys):
    """Each output sample of the documents is what its command prints (a line ending in
    ``, ...`` is the start of a printed line): samples do not drift from the program."""
    monkeypatch.chdir(tmp_path)
    for command, lines in _samples(path):
        capsys.readouterr()
        assert main(shlex.split(command)[1:]) == 0, command
        printed = capsys.readouterr().out.splitlines()
        for line in lines:
            if line.endswith(", ..."):
                assert any(p.startswith(line[:-3]) for p in printed), f"{command}: {line}"
            else:
                assert line in printed, f"{command}: {line}"


def test_the_guide_documents_every_command():
    commands = {shlex.split(c)[1] for c, _ in _commands(ROOT / "docs" / "guide.md")
                if c.startswith("groove ") and not c.startswith("groove --")}
    parser = build_parser()
    available = set(parser._subparsers._group_actions[0].choices)
    assert available <= commands


def _anchors(path: Path) -> set[str]:
    """The anchors GitHub gives the headings of a markdown file: lower case, spaces as hyphens,
    other punctuation dropped."""
    headings = re.findall(r"^#+ (.+)$", FENCE.sub("", path.read_text()), re.MULTILINE)
    return {re.sub(r"[^\w\- ]", "", h.strip().lower()).replace(" ", "-") for h in headings}


@pytest.mark.parametrize("path", DOCUMENTS, ids=lambda p: p.name)
def test_links_resolve(path):
    for target, anchor in re.findall(r"\]\(([^)#\s]*)(?:#([^)\s]*))?\)", path.read_text()):
        if re.match(r"[a-z]+:", target):
            continue
        linked = path.parent / target if target else path
        assert linked.exists(), f"{path.name} links to missing {target}"
        if anchor and linked.suffix == ".md":  # a section of it (it read #groove-audit)
            assert anchor in _anchors(linked), f"{path.name} links to missing {target}#{anchor}"


def test_nothing_points_to_files_outside_the_repository():
    sources = [*DOCUMENTS, ROOT / "CHANGELOG.md",
               *(ROOT / "groove_model").rglob("*.py"), *(ROOT / "continuation").rglob("*.py")]
    for path in sources:
        assert "shared/" not in path.read_text(), f"{path.relative_to(ROOT)} cites shared/"
