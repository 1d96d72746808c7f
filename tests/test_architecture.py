"""The shape of the code, read with ``ast``: imports, layers, sizes.

Every import counts, also one inside a function: a function-local import still ties two
modules together (and a circle hidden that way is still a circle).
"""

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "groove_model"

#: Layers of groove_model, lowest first: a module imports only from its own layer or lower.
LAYERS = {"model": 0, "tracing": 1, "analysis": 2, "io": 2, "plots": 3, "cli": 4}
#: Numerical layers: no plotting or data-frame library.
NUMERICAL = ("model", "analysis")
MAX_MODULE_LINES = 600
MAX_FUNCTION_LINES = 80
#: Modules exempt from the size limits (none).
SIZE_EXEMPT: set[str] = set()
#: Private names tests may still import, with the reason.
PRIVATE_IMPORTS_ALLOWED: set[tuple[str, str]] = set()


def _modules(package: Path):
    """``{dotted name: path}`` of every module below ``package``."""
    return {".".join(path.relative_to(ROOT).with_suffix("").parts).removesuffix(".__init__"):
            path for path in sorted(package.rglob("*.py"))}


def _imports(name: str, path: Path, tree: ast.Module):
    """``(imported module, node)`` for every import in the module, absolute names."""
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                yield alias.name, node
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                base = base[: len(base) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module
            if node.module:  # ``from . import tracer`` imports the module, not the package
                yield target, node
            for alias in node.names:
                yield f"{target}.{alias.name}", node


def _graph(modules):
    """Import graph restricted to ``modules``: ``{module: {imported modules}}``."""
    graph = {}
    for name, path in modules.items():
        tree = ast.parse(path.read_text())
        graph[name] = {target for target, _ in _imports(name, path, tree)
                       if target in modules and target != name}
    return graph


GROOVE = _modules(PACKAGE)
CONTINUATION = _modules(ROOT / "continuation")
TREES = {name: ast.parse(path.read_text()) for name, path in {**GROOVE, **CONTINUATION}.items()}


def _layer(module: str):
    parts = module.split(".")
    return LAYERS.get(parts[1]) if len(parts) > 1 else None


def _top_level(module: str):
    return module.split(".")[0]


def test_groove_model_has_no_import_circle():
    graph = _graph(GROOVE)
    # The package's own __init__ hands names on lazily; every submodule "imports" it.
    graph = {m: {t for t in targets if t != "groove_model"} for m, targets in graph.items()}
    state, stack = {}, []

    def visit(module):
        state[module] = "open"
        stack.append(module)
        for target in sorted(graph[module]):
            if state.get(target) == "open":
                circle = stack[stack.index(target):] + [target]
                pytest.fail("import circle: " + " -> ".join(circle))
            if target not in state:
                visit(target)
        stack.pop()
        state[module] = "done"

    for module in sorted(graph):
        if module not in state:
            visit(module)


def test_imports_run_down_the_layers():
    for name, targets in _graph(GROOVE).items():
        here = _layer(name)
        if here is None:
            continue
        for target in targets:
            there = _layer(target)
            assert there is None or there <= here, f"{name} (layer {here}) imports {target} " \
                                                   f"(layer {there})"


def test_continuation_imports_nothing_of_groove_model_pandas_or_matplotlib():
    for name, path in CONTINUATION.items():
        for target, node in _imports(name, path, TREES[name]):
            assert _top_level(target) not in ("groove_model", "pandas", "matplotlib"), \
                f"{name}:{node.lineno} imports {target}"


@pytest.mark.parametrize("layer", NUMERICAL)
def test_numerical_layers_import_neither_matplotlib_nor_pandas(layer):
    for name, path in GROOVE.items():
        if name.split(".")[1:2] != [layer]:
            continue
        for target, node in _imports(name, path, TREES[name]):
            assert _top_level(target) not in ("pandas", "matplotlib"), \
                f"{name}:{node.lineno} imports {target}"


def test_only_the_command_line_imports_argparse():
    for name, path in GROOVE.items():
        if name.startswith("groove_model.cli"):
            continue
        for target, node in _imports(name, path, TREES[name]):
            assert target != "argparse", f"{name}:{node.lineno} imports argparse"


def _functions(tree):
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            yield node


def test_a_function_local_import_says_why():
    for name, path in GROOVE.items():
        lines = path.read_text().splitlines()
        for function in _functions(TREES[name]):
            for node in ast.walk(function):
                if not isinstance(node, (ast.Import, ast.ImportFrom)):
                    continue
                above = node.lineno - 2
                while above >= 0 and lines[above].strip().startswith(("from ", "import ")):
                    above -= 1  # the first import of a group carries the comment
                inline = "#" in lines[node.lineno - 1]
                assert inline or lines[above].strip().startswith("#"), \
                    f"{path.relative_to(ROOT)}:{node.lineno}: a function-local import " \
                    "needs a comment saying why"


def test_no_module_is_over_600_lines():
    for _name, path in {**GROOVE, **CONTINUATION}.items():
        if path.name in SIZE_EXEMPT:
            continue
        n = len(path.read_text().splitlines())
        assert n <= MAX_MODULE_LINES, f"{path.relative_to(ROOT)} has {n} lines"


def _code_lines(function: ast.FunctionDef) -> int:
    """Lines of a function, without its docstring."""
    body = function.body
    first = body[0]
    if isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant) \
            and isinstance(first.value.value, str):
        docstring = first.end_lineno - first.lineno + 1
    else:
        docstring = 0
    return function.end_lineno - function.lineno + 1 - docstring


def _kept_whole(function: ast.FunctionDef, lines: list[str]) -> bool:
    """Whether the function's code opens with a comment ``# kept whole: <why>``."""
    body = function.body
    first = body[1] if len(body) > 1 and isinstance(body[0], ast.Expr) else body[0]
    # the comment stands on the line(s) between the docstring and the first statement
    above = lines[(body[0].end_lineno if first is not body[0] else function.lineno):
                  first.lineno - 1]
    return any(line.strip().startswith("# kept whole:") for line in above)


def test_no_function_is_over_80_lines():
    """No function over 80 lines without its docstring, unless it says why it stays whole."""
    for name, path in {**GROOVE, **CONTINUATION}.items():
        if path.name in SIZE_EXEMPT:
            continue
        lines = path.read_text().splitlines()
        for function in _functions(TREES[name]):
            if _kept_whole(function, lines):
                continue
            n = _code_lines(function)
            assert n <= MAX_FUNCTION_LINES, \
                f"{path.relative_to(ROOT)}:{function.lineno} {function.name} has {n} lines"


def _private(name: str) -> bool:
    return name.startswith("_") and not name.startswith("__")


def test_tests_import_no_private_name_of_another_package():
    for path in sorted((ROOT / "tests").rglob("*.py")):
        tree = ast.parse(path.read_text())
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom) and node.module and not node.level:
                for alias in node.names:
                    private = any(_private(part)
                                  for part in [*node.module.split("."), alias.name])
                    if private and (node.module, alias.name) not in PRIVATE_IMPORTS_ALLOWED:
                        pytest.fail(f"{path.relative_to(ROOT)}:{node.lineno} imports "
                                    f"{alias.name} from {node.module}")
