"""The package read from its source: no module imports a private name of a sibling, the imports
made when a module loads form no cycle, and every public function that raises says what."""

import ast
import pathlib

PACKAGE = pathlib.Path(__file__).resolve().parents[2] / "python" / "fairlines"
#: Private modules meant to be shared inside the package.
SHARED_PRIVATE = {"_native", "_options"}


def _modules() -> dict[str, tuple[ast.Module, bool]]:
    """Dotted name inside the package ("" for the package itself) -> (syntax tree, is a package)."""
    out = {}
    for path in PACKAGE.rglob("*.py"):
        parts = path.relative_to(PACKAGE).with_suffix("").parts
        is_package = parts[-1] == "__init__"
        name = ".".join(parts[:-1] if is_package else parts)
        out[name] = (ast.parse(path.read_text(encoding="utf-8")), is_package)
    return out


def _targets(module: str, is_package: bool, node: ast.ImportFrom) -> list[tuple[str, str]]:
    """(package module, imported name) of each name a `from ... import` takes from the package."""
    if node.level == 0:
        if not (node.module or "").startswith("fairlines"):
            return []
        base = node.module.removeprefix("fairlines").lstrip(".")
    else:
        package = module if is_package else module.rpartition(".")[0]
        parts = package.split(".") if package else []
        parts = parts[: len(parts) - (node.level - 1)]
        base = ".".join(parts + ([node.module] if node.module else []))
    return [(base, a.name) for a in node.names]


def test_no_module_imports_a_private_name_of_a_sibling():
    modules, found = _modules(), []
    for module, (tree, is_package) in modules.items():
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom):
                for base, name in _targets(module, is_package, node):
                    shared = base.split(".")[-1] in SHARED_PRIVATE or name in SHARED_PRIVATE
                    if name.startswith("_") and not name.startswith("__") and not shared:
                        found.append(f"{module or 'fairlines'} imports {name} from {base or 'fairlines'}")
    assert found == []


def test_module_level_imports_form_no_cycle():
    modules = _modules()
    graph = {m: set() for m in modules}
    for module, (tree, is_package) in modules.items():
        for node in tree.body:  # what runs when the module loads
            if isinstance(node, ast.ImportFrom):
                for base, name in _targets(module, is_package, node):
                    sub = f"{base}.{name}".lstrip(".")
                    target = sub if sub in modules else base
                    if target in modules and target != module and target != "":
                        graph[module].add(target)
    state, cycles = {}, []

    def visit(m, path):
        state[m] = "open"
        for n in sorted(graph[m]):
            if state.get(n) == "open":
                cycles.append(path[path.index(n):] + [n])
            elif n not in state:
                visit(n, path + [n])
        state[m] = "done"

    for m in sorted(graph):
        if m not in state:
            visit(m, [m])
    assert cycles == []


def test_every_public_function_that_raises_names_what_in_its_docstring():
    """A public module-level function with a raise statement documents it ("Raises ...")."""
    silent = []
    for module, (tree, _) in _modules().items():
        for node in tree.body:
            if isinstance(node, ast.FunctionDef) and not node.name.startswith("_"):
                raises = any(isinstance(n, ast.Raise) for n in ast.walk(node))
                if raises and "raise" not in (ast.get_docstring(node) or "").lower():
                    silent.append(f"{module}.{node.name}")
    assert silent == []


def _private_attribute_uses(package_dir: pathlib.Path, shared: set) -> list[str]:
    """`module._name` where `module` is bound by a relative import (a sibling module of the
    package) and not one of the `shared` private modules."""
    found = []
    for path in sorted(package_dir.rglob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        siblings = {a.asname or a.name: a.name for node in ast.walk(tree)
                    if isinstance(node, ast.ImportFrom) and node.level > 0 for a in node.names}
        for node in ast.walk(tree):
            if (isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id in siblings
                    and siblings[node.value.id] not in shared
                    and node.attr.startswith("_") and not node.attr.startswith("__")):
                found.append(f"{path.relative_to(package_dir)}:{node.lineno} uses {node.value.id}.{node.attr}")
    return found


def test_no_module_uses_a_private_name_of_a_sibling_module():
    assert _private_attribute_uses(PACKAGE, SHARED_PRIVATE) == []


def test_imports_anywhere_form_no_cycle():
    """The imports inside functions count too: a late import hides a cycle, it does not remove
    it. The package's __init__ (which imports every module to re-export it) and the compiled
    _native (no source) are left out."""
    from test_addon_import_graph import find_cycle, import_graph

    graph = {m: edges - {""} for m, edges in import_graph(str(PACKAGE)).items() if m != ""}
    cycle = find_cycle(graph)
    assert cycle is None, " -> ".join(cycle)


def _public_methods(tree: ast.Module):
    """(class name, method) of every public method of the module's public classes."""
    for cls in tree.body:
        if isinstance(cls, ast.ClassDef) and not cls.name.startswith("_"):
            for node in cls.body:
                if isinstance(node, ast.FunctionDef) and not node.name.startswith("_"):
                    yield cls.name, node


def _says_what_it_raises(node: ast.FunctionDef) -> bool:
    raises = any(isinstance(n, ast.Raise) for n in ast.walk(node))
    return not raises or "raise" in (ast.get_docstring(node) or "").lower()


def test_every_public_method_that_raises_names_what_in_its_docstring():
    """A public method of a public class with a raise statement documents it ("Raises ...")."""
    silent = [f"{module}.{cls}.{node.name}" for module, (tree, _) in _modules().items()
              for cls, node in _public_methods(tree) if not _says_what_it_raises(node)]
    assert silent == []
