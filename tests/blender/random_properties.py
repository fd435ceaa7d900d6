"""Randomized property check, run inside Blender by blender_checks.py: one node of every
Fairlines type in one tree, each data input linked from an earlier node of the right kind,
then seeded rounds that set a few input-socket defaults and node properties to random,
extreme and degenerate values (NaN, +-inf, 0, -0, negative, huge, empty or odd strings, missing
files), evaluate through the scripting API and restore them. After every evaluation each node
must be OK, or red / blocked with a message; nothing may raise (test_blender.py also fails on
any traceback in Blender's output, which is where update callbacks would print one).
"""

import math
import os
import random
import time

import bpy

FLOATS = (math.nan, math.inf, -math.inf, 0.0, -0.0, -1.0, 1e-300, -1e-300, 1e300, -1e300, 1e9, -1e9,
          1e6, 0.5, 2.0)
INTS = (0, -1, 1, 2, 3, -2**31, 2**31 - 1, 10**6, -10**6, 10**9, 2**63)
STRINGS = ("", " ", "x" * 5000, "\u00e9\u6f22\u5b57\U0001F6A2", "../../..", "{", "null", "%s%n", "\t\n")


class Refused(Exception):
    """Blender's RNA refused the value (type or range): a normal outcome, counted."""


def junk_files(tmp):
    """File paths for FILE_PATH properties, all inside tmp: missing, a directory, empty,
    binary, truncated JSON / CSV, and a huge number in text."""
    os.makedirs(tmp, exist_ok=True)
    files = {"empty.json": b"", "binary.csv": bytes(range(256)) * 4, "trunc.json": b'{"principal": {"Lpp": 1',
             "list.json": b"[1,2,3]", "nan.csv": b"x,y,z\nnan,inf,-inf\n1e308,1e308,1e308\n",
             "header.csv": b"station,waterline,half_breadth\n", "huge.dat": b"VARIABLES = X Y Z\nZONE I=99999999\n"}
    paths = ["", os.path.join(tmp, "missing", "nothing.json"), tmp]
    for name, data in files.items():
        path = os.path.join(tmp, name)
        with open(path, "wb") as f:
            f.write(data)
        paths.append(path)
    return paths


def random_value(rng, prop, current, paths):
    """A random value for an RNA property (bpy.types.Property), chosen among extreme ones."""
    kind = prop.type
    if kind == "FLOAT":
        pick = lambda: rng.choice(FLOATS) if rng.random() < 0.8 else rng.uniform(-1e3, 1e3)  # noqa: E731
        return tuple(pick() for _ in range(prop.array_length)) if prop.array_length else pick()
    if kind == "INT":
        return rng.choice(INTS) if rng.random() < 0.8 else rng.randint(-100, 1000)
    if kind == "BOOLEAN":
        return not current
    if kind == "ENUM":
        return rng.choice([item.identifier for item in prop.enum_items])
    if kind == "STRING":
        return rng.choice(paths) if prop.subtype == "FILE_PATH" else rng.choice(STRINGS)
    if kind == "POINTER":
        pool = {"Object": bpy.data.objects, "Collection": bpy.data.collections, "Text": bpy.data.texts}
        items = list(pool.get(prop.fixed_type.identifier, ()))
        return rng.choice(items + [None])
    raise Refused("property type %s" % kind)


def targets(tree):
    """(node, owner, attribute, rna property) for every value socket and every node property."""
    out = []
    for node in tree.nodes:
        for sock in node.inputs:
            if hasattr(sock, "default_value") and not sock.is_linked:
                out.append((node, sock, "default_value", sock.bl_rna.properties["default_value"]))
                if getattr(sock, "is_optional", False):
                    out.append((node, sock, "use", sock.bl_rna.properties["use"]))
        for name in node.params:
            out.append((node, node, name, node.bl_rna.properties[name]))
    return out


def build(api, ids, name, prepare):
    """Every node type once, in menu order; each data input (a socket with no value) linked
    from the nearest earlier node with an output of that kind, preferring one that evaluates
    OK (so that random values reach working inputs); only earlier nodes, so no cycle."""
    tree = api.new_tree(name)
    nodes = []
    for k, label in enumerate(api.node_types()):
        node = api.add(tree, label, location=(300.0 * k, 0.0))
        for sock in node.inputs:
            if hasattr(sock, "default_value"):
                continue
            kind = [(src, next((o for o in src.outputs if o.bl_idname == sock.bl_idname), None))
                    for src in reversed(nodes)]
            kind = [(src, out) for src, out in kind if out is not None]
            kind.sort(key=lambda pair: pair[0].fl_state != "OK")  # stable: nearest OK first
            if kind:
                tree.links.new(kind[0][1], sock)
        nodes.append(node)
        prepare(tree)
        api.evaluate(tree, check=False)
    return tree


def _assign(owner, attr, value):
    try:
        setattr(owner, attr, value)
    except (TypeError, ValueError, OverflowError) as exc:
        raise Refused(str(exc))


def give_sources(tree, points, files):
    """Working inputs for the nodes that read the scene or files, set before the random rounds
    (random values may switch them to junk and back)."""
    for node in tree.nodes:
        if node.bl_idname == "FLNodePointsFromObject":
            node.source, node.columns = points, 6
        elif node.bl_idname == "FLNodeOffsetsImport" and os.path.exists(files["offsets"]):
            node.filepath = files["offsets"]
        elif node.bl_idname == "FLNodeHullDescription":
            node.filepath = files["description"]


def run(api, ids, check, tmp, points, files, seed=17, changes=1500, per_round=4):
    """Returns counts for the report; fails through check() on a node red without a message,
    a node left unevaluated, or any exception out of the evaluation."""
    rng = random.Random(seed)
    paths = junk_files(tmp) + [f for f in files.values() if os.path.exists(f)]
    tree = build(api, ids, "Random Properties", lambda t: give_sources(t, points, files))
    api.evaluate(tree, check=False)
    every = targets(tree)
    done = refused = evaluations = 0
    states, last_message = {}, {}
    t0 = time.perf_counter()
    while done < changes:
        chosen = rng.sample(every, per_round)
        saved = [getattr(owner, attr) for _, owner, attr, _ in chosen]
        saved = [tuple(v) if hasattr(v, "__len__") and not isinstance(v, str) else v for v in saved]
        for (node, owner, attr, prop), old in zip(chosen, saved):
            try:
                _assign(owner, attr, random_value(rng, prop, old, paths))
                done += 1
            except Refused:
                refused += 1
        api.evaluate(tree, check=False)
        evaluations += 1
        for node in tree.nodes:
            check(node.fl_state in ("OK", "ERROR", "BLOCKED"), "%s: state %r after random values" % (
                node.name, node.fl_state))
            check(node.fl_state == "OK" or node.fl_message.strip(), "%s: %s without a message" % (
                node.name, node.fl_state))
            states.setdefault(node.bl_idname, set()).add(node.fl_state)
            if node.fl_state != "OK":
                last_message[node.bl_idname] = node.fl_message[:160]
        for (node, owner, attr, prop), old in zip(chosen, saved):
            _assign(owner, attr, old)
    api.evaluate(tree, check=False)
    seconds = time.perf_counter() - t0
    never_ok = {k: last_message[k] for k, v in sorted(states.items()) if "OK" not in v}
    bpy.data.node_groups.remove(tree)
    return {"changes": done, "refused_by_rna": refused, "evaluations": evaluations, "targets": len(every),
            "node_types": len(states), "never_ok": never_ok,
            "types_red_at_least_once": sum("ERROR" in v for v in states.values()), "seconds": round(seconds, 1)}
