"""The modules of rollaway import each other without circles, and its packages in one order: a package imports
only those below it (every import statement counts, lazy ones too)."""
import ast
from pathlib import Path

import rollaway

SRC = Path(rollaway.__file__).parent


def module_name(path: Path) -> str:
    parts = path.relative_to(SRC.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def import_graph() -> dict[str, set[str]]:
    """Module -> rollaway modules it names in an import statement (a name imported from a package is
    the submodule when one exists, else the package)."""
    modules = {module_name(p): p for p in SRC.rglob("*.py")}
    graph = {}
    for name, path in modules.items():
        package = name if path.name == "__init__.py" else name.rsplit(".", 1)[0]
        edges = set()
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Import):
                edges |= {a.name for a in node.names if a.name in modules}
            elif isinstance(node, ast.ImportFrom):
                base = node.module or ""
                if node.level:
                    base = ".".join(package.split(".")[:len(package.split(".")) - node.level + 1] + ([base] if base else []))
                for a in node.names:
                    sub = f"{base}.{a.name}"
                    edges.add(sub if sub in modules else base)
        graph[name] = {e for e in edges if e in modules and e != name}
    return graph


def cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components with more than one module (Tarjan)."""
    index, low, stack, on, out = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in graph[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def test_the_checker_finds_a_circle():
    assert cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]


def test_the_graph_sees_lazy_imports():
    graph = import_graph()
    assert "rollaway.model.model_file" in graph["rollaway.model.drum_model"]          # inside DrumModel.__init__
    assert "rollaway.hold.numeric" in graph["rollaway.hold.closed_form"]


def test_no_import_circles():
    assert cycles(import_graph()) == []


# Lowest first.  Top-level helper modules (errors, jsonsafe, display, callable_module, _moved) sit below all.
PACKAGE_ORDER = ["physics", "bench", "effects", "model", "hold", "uncertainty", "sim", "sweep", "figures",
                 "identify", "risk", "export", "api", "cli"]
FOUNDATION = {"errors", "jsonsafe", "display", "callable_module", "_moved", "__main__", "scipy_direct"}


def package_of(module: str) -> str:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else ""


def test_the_order_check_sees_a_back_arrow():
    assert back_arrows({"rollaway.model.chain": {"rollaway.sim.run"}}) == [("rollaway.model.chain", "rollaway.sim.run")]
    assert back_arrows({"rollaway.sim.run": {"rollaway.model.chain"}}) == []


def back_arrows(graph: dict[str, set[str]]) -> list[tuple[str, str]]:
    """(importer, imported) pairs where a package imports one above it (or a foundation module a package)."""
    rank = {p: i for i, p in enumerate(PACKAGE_ORDER)}
    out = []
    for mod, edges in graph.items():
        pm = package_of(mod)
        for e in edges:
            pe = package_of(e)
            if pe in ("", pm) or pe in FOUNDATION and pm not in FOUNDATION:
                continue
            if pm in FOUNDATION or pm == "" and mod != "rollaway":
                if mod != "rollaway.__main__":
                    out.append((mod, e))
            elif rank.get(pe, -1) > rank.get(pm, len(rank)):
                out.append((mod, e))
    return sorted(out)


def test_every_package_is_in_the_order():
    packages = {package_of(m) for m in import_graph()} - {""} - FOUNDATION
    assert packages <= set(PACKAGE_ORDER), packages - set(PACKAGE_ORDER)


def test_no_package_imports_one_above_it():
    assert back_arrows(import_graph()) == []


def test_bench_knows_nothing_of_the_model():
    graph = import_graph()
    for mod, edges in graph.items():
        if package_of(mod) == "bench":
            assert not {e for e in edges if package_of(e) in ("identify", "model", "effects", "uncertainty")}, mod
