"""The Blender add-on's modules import one another without a cycle, counting the imports made
inside functions too (a late import hides a cycle, it does not remove it). Read from the source
with ast, so no Blender is needed."""

import ast
import os

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
ADDON = os.path.join(ROOT, "addon")


def _modules(package_dir):
    """{dotted name relative to the package ("" for its __init__): file path}."""
    out = {}
    for folder, _, files in os.walk(package_dir):
        rel = os.path.relpath(folder, package_dir)
        parts = [] if rel == "." else rel.split(os.sep)
        for f in files:
            if f.endswith(".py"):
                name = parts + ([] if f == "__init__.py" else [f[:-3]])
                out[".".join(name)] = os.path.join(folder, f)
    return out


def _join(*parts):
    return ".".join(p for p in parts if p)


def import_graph(package_dir):
    """{module: set of the package's modules it imports}, relative imports at any depth."""
    modules = _modules(package_dir)
    graph = {}
    for name, path in modules.items():
        package = name if path.endswith("__init__.py") else name.rpartition(".")[0]
        edges = set()
        with open(path, encoding="utf-8") as f:
            tree = ast.parse(f.read(), path)
        for node in ast.walk(tree):
            if not isinstance(node, ast.ImportFrom) or node.level == 0:
                continue
            base = package.split(".") if package else []
            base = base[:len(base) - (node.level - 1)] if node.level > 1 else base
            target = _join(".".join(base), node.module or "")
            for alias in node.names:
                sub = _join(target, alias.name)
                edges.add(sub if sub in modules else target)
        graph[name] = edges - {name}
    return graph


def find_cycle(graph):
    """One import cycle as a list of modules, or None."""
    state, stack = {}, []

    def visit(m):
        state[m] = "open"
        stack.append(m)
        for n in sorted(graph.get(m, ())):
            if state.get(n) == "open":
                return stack[stack.index(n):] + [n]
            if n not in state:
                found = visit(n)
                if found:
                    return found
        stack.pop()
        state[m] = "done"
        return None

    for m in sorted(graph):
        if m not in state:
            found = visit(m)
            if found:
                return found
    return None


def test_addon_imports_are_acyclic():
    graph = import_graph(ADDON)
    assert {"props", "evaluator", "sockets", "nodes.base"} <= set(graph)
    assert find_cycle(graph) is None, " -> ".join(find_cycle(graph))


def test_a_late_import_cycle_is_found(tmp_path):
    pkg = tmp_path / "pkg"
    (pkg / "sub").mkdir(parents=True)
    (pkg / "__init__.py").write_text("")
    (pkg / "a.py").write_text("from .sub import b\n")
    (pkg / "sub" / "__init__.py").write_text("")
    (pkg / "sub" / "b.py").write_text("def f():\n    from .. import a\n")
    graph = import_graph(str(pkg))
    assert graph["a"] == {"sub.b"} and graph["sub.b"] == {"a"}
    assert find_cycle(graph) == ["a", "sub.b", "a"]


def test_addon_modules_import_no_private_name_of_a_sibling():
    """Neither `from .x import _y` nor `x._y` on a sibling module `x`: what modules share is public."""
    found = []
    for name, path in sorted(_modules(ADDON).items()):
        with open(path, encoding="utf-8") as f:
            tree = ast.parse(f.read(), path)
        siblings = set()
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom) and node.level > 0:
                for alias in node.names:
                    siblings.add(alias.asname or alias.name)
                    if alias.name.startswith("_") and not alias.name.startswith("__"):
                        found.append("%s imports %s" % (name, alias.name))
        for node in ast.walk(tree):
            if (isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id in siblings
                    and node.attr.startswith("_") and not node.attr.startswith("__")):
                found.append("%s:%d uses %s.%s" % (name, node.lineno, node.value.id, node.attr))
    assert found == []
