"""The rotbeam package's modules import one another without a cycle: every import statement of
every module (at the top, in a function, under `if __name__ == "__main__"`) read from the source
(python/rotbeam/*.py, with ast: nothing is imported), and the graph of rotbeam's modules that they
make has no cycle. A cycle is named with its modules and the lines that close it. Pure Python: runs
without the extension module built."""

import ast
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[2] / "python" / "rotbeam"


def module_name(path):
    return "rotbeam" if path.stem == "__init__" else f"rotbeam.{path.stem}"


def imports_of(path, modules):
    """{imported module of `modules`: first line importing it} of the module file `path`. `from . import
    name` is the module rotbeam.name where there is one, else the package itself (its __init__)."""
    found = {}

    def add(name, line):
        if name in modules and name != module_name(path):
            found.setdefault(name, line)

    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), str(path))):
        if isinstance(node, ast.Import):
            for alias in node.names:
                add(alias.name, node.lineno)
        elif isinstance(node, ast.ImportFrom):
            base = "rotbeam" if node.level else node.module or ""
            if node.level and node.module:
                base = f"rotbeam.{node.module}"
            if base == "rotbeam":
                for alias in node.names:
                    add(f"rotbeam.{alias.name}" if f"rotbeam.{alias.name}" in modules else "rotbeam", node.lineno)
            else:
                add(base, node.lineno)
    return found


def import_graph(folder=PACKAGE):
    """{module: {module it imports: line}} of the package's modules (the extension module rotbeam._core,
    known by its type stubs _core.pyi, imports none of them)."""
    files = {module_name(p): p for p in sorted(folder.glob("*.py"))}
    modules = set(files) | {module_name(p) for p in folder.glob("*.pyi")}
    return {name: imports_of(path, modules) for name, path in files.items()}


def cycles(graph):
    """The strongly connected components of more than one module (Tarjan), each a sorted list."""
    index, low, stack, on_stack, found = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in graph.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return found


def test_the_cycle_finder_finds_a_cycle():
    assert cycles({"a": {"b": 1}, "b": {"c": 1}, "c": {"a": 1}, "d": {"a": 1}}) == [["a", "b", "c"]]
    assert cycles({"a": {"b": 1}, "b": {}}) == []


def test_the_graph_is_read():
    graph = import_graph()
    assert "rotbeam.plots" in graph and "rotbeam" in graph
    assert "rotbeam.run_plots" in graph["rotbeam.plots"]  # `from .run_plots import …`
    assert "rotbeam._interrupt" in graph["rotbeam.plots"]  # `from rotbeam._interrupt import …`
    assert "rotbeam.animate" in graph["rotbeam.plots"]  # inside a function
    assert "rotbeam" in graph["rotbeam.animate"]  # `from . import _arguments`: the package's own name
    assert "rotbeam._core" in graph["rotbeam._sweep"]  # `from . import _core`: the extension module


def test_no_import_cycle_among_rotbeam_modules():
    graph = import_graph()
    found = cycles(graph)
    described = ["; ".join(f"{a} imports {b} (line {graph[a][b]})" for a in c for b in c if b in graph[a])
                 for c in found]
    assert not found, "import cycles: " + " | ".join(described)
