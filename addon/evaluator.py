"""Live evaluation of Fairlines trees.

Every node's result is cached with a *key*: its type, its own property values, the values of
its unlinked input sockets, and the (node, socket, version) of each linked input. Evaluating a
tree walks it in dependency order and re-runs a node only when its key changed, so a property
change re-runs exactly that node and the nodes downstream of it; everything upstream is served
from the cache. Because the key is rebuilt from the current properties, undo, redo and file
load need no special bookkeeping: whatever changed is re-run.

Property changes do not evaluate inside the update callback (that would run in the middle of a
slider drag and stall the UI); they queue the tree and a zero-delay timer evaluates it once,
coalescing a burst of changes into one evaluation. The timer works in slices of about
SLICE_MS: when a slice is used up between two nodes it hands control back to Blender's event
loop and carries on at the next tick, so a long graph does not freeze the interface (the cache
keys make resuming trivial: nodes already re-run are up to date).

Deferred work: a node may hand back part of its work as a job (``"__later__"`` in its outputs)
for outputs and info that nothing may need at once, such as the bare hull's hydrostatics. The
job runs when a downstream node reads one of the outputs it provides, or else after the whole
tree has been evaluated: from the timer, one tick later, so that Blender first redraws with the
new meshes; from flush(), before it returns. Either way every value ends up as if the node had
computed it all in one go; a job never delays the mesh when nothing downstream reads its outputs.
"""

import atexit
import time

import bpy

from . import engine, progress, queue
from .nodes.base import ERROR_COLOUR, FairlinesNode, NodeError
from .sockets import compatible


class Entry:
    __slots__ = ("key", "outputs", "version", "ms", "ok", "later", "info")

    def __init__(self, key, outputs, version, ms, ok, later=None, info=""):
        self.key, self.outputs, self.version, self.ms, self.ok = key, outputs, version, ms, ok
        self.later, self.info = later, info  # deferred job (or None) and the info shown before it


SLICE_MS = 30.0
_cache = {}          # (tree name, node name) -> Entry
_pending = queue.pending  # names of trees waiting for evaluation (queue.py fills it)
_deferred = []       # cache keys of entries that still hold a deferred job, oldest first
last_stats = {"tree": "", "evaluated": [], "ms": 0.0}


is_fairlines_tree = queue.is_fairlines_tree
request = queue.push  # queue a tree for evaluation


def _wake():
    # Ask Blender, not a flag of ours, whether the timer is live: Blender can drop timers
    # (file load, undo) without calling them. A running timer picks the tree up before it
    # stops (it returns None only when nothing is pending).
    if not bpy.app.timers.is_registered(_on_timer):
        bpy.app.timers.register(_on_timer, first_interval=0.0, persistent=True)


queue.set_waker(_wake)


def drop_timer():
    if bpy.app.timers.is_registered(_on_timer):
        bpy.app.timers.unregister(_on_timer)


# The bpy module of Blender 4.2 crashes at interpreter exit when a Python timer is still
# registered (it has no event loop, so a queued evaluation can be pending then); 5.0 does not.
# Dropping ours first is harmless everywhere.
atexit.register(drop_timer)


def _on_timer():
    try:
        flush(deadline=time.perf_counter() + SLICE_MS * 1e-3)
    except Exception as exc:
        # Node failures are caught per node; this is the evaluator itself failing (e.g. data
        # removed while it ran). Say so in one line, drop the queue, and keep Blender going:
        # the next change queues the tree again.
        print("Fairlines: evaluation stopped: %s: %s" % (type(exc).__name__, exc))
        _pending.clear()
        return None
    if _pending or _deferred:
        return 0.0  # more to do: run again right after Blender has handled its events
    return None


def flush(deadline=None, later=True):
    """Evaluate every queued tree, then run the deferred jobs (the timer does this in slices
    and leaves the jobs to a later tick than the trees, so the new meshes are drawn first;
    tests and scripts call it without a deadline to finish now). later=False leaves the
    deferred jobs queued (the latency bench times the meshes alone that way)."""
    evaluated = False
    while _pending or (later and _deferred):
        while _pending:
            name = _pending.pop()
            tree = bpy.data.node_groups.get(name)
            if is_fairlines_tree(tree):
                evaluate(tree, deadline)
                evaluated = True
                if deadline is not None and time.perf_counter() > deadline:
                    return
        if not later or (deadline is not None and evaluated):
            return
        _run_deferred(deadline)
        if deadline is not None and time.perf_counter() > deadline:
            return


def _run_deferred(deadline=None):
    """Run queued deferred jobs, oldest first, until done or past the deadline."""
    while _deferred:
        ckey = _deferred.pop(0)
        tree = bpy.data.node_groups.get(ckey[0])
        entry = _cache.get(ckey)
        node = tree.nodes.get(ckey[1]) if is_fairlines_tree(tree) else None
        if entry is not None and entry.later is not None and node is not None:
            _finish(tree, node, entry)
        if deadline is not None and time.perf_counter() > deadline:
            return


def _finish(tree, node, entry):
    """Run an entry's deferred job: its outputs join the entry's, its info the node's. A failing
    job fails the node as a failing compute() would: red, outputs dropped, and its version bumped
    so that the nodes which already used it re-run (and show they are blocked)."""
    job, entry.later = entry.later, None
    t0 = time.perf_counter()
    try:
        more = job() or {}
        ok, message = True, ""
    except Exception as exc:
        more, ok, message = {}, False, _message(exc)
    entry.ms += (time.perf_counter() - t0) * 1e3
    busy, queue.busy = queue.busy, True  # writing the node's status must not queue an evaluation
    try:
        if ok:
            info = entry.info + more.pop("__info__", "")
            entry.outputs.update(more)
            _show(node, "OK", "", entry.ms, info)
        else:
            entry.ok, entry.outputs = False, {}
            entry.version += 1
            _show(node, "ERROR", message, entry.ms)
    finally:
        queue.busy = busy
    if not ok:
        _pending.add(tree.name)  # the nodes downstream of it must now show they are blocked
        _wake()


def clear(tree_name=None, outputs_only=False):
    for key in list(_cache):
        if tree_name is not None and key[0] != tree_name:
            continue
        if outputs_only:
            tree = bpy.data.node_groups.get(key[0])
            node = tree.nodes.get(key[1]) if tree is not None else None
            if node is not None and not getattr(node, "is_output", False):
                continue
        del _cache[key]


def evaluate_all():
    for tree in bpy.data.node_groups:
        if is_fairlines_tree(tree):
            evaluate(tree)


def outputs_of(tree, node_name):
    entry = _cache.get((tree.name, node_name))
    node = tree.nodes.get(node_name)
    if entry is not None and entry.later is not None and node is not None:
        _finish(tree, node, entry)  # whoever asks gets every output
    return None if entry is None or not entry.ok else entry.outputs


def peek(tree, node_name):
    """The cache entry of a node without running its deferred job (for drawing), or None."""
    return _cache.get((tree.name, node_name))


def _link_map(tree):
    """{input socket pointer: link} in one pass. NodeSocket.links scans every link of the
    tree on each access; asking it per socket made the walk quadratic in the graph size."""
    return {link.to_socket.as_pointer(): link for link in tree.links}


def _source(socket, links):
    """The output socket feeding `socket`, through reroutes; None when unlinked."""
    for _ in range(64):
        link = links.get(socket.as_pointer())
        if link is None or not link.is_valid or getattr(link, "is_muted", False):
            return None
        src = link.from_socket
        if src.node.bl_idname != "NodeReroute":
            return src
        socket = src.node.inputs[0]
    return None


def _order(tree, links):
    """Fairlines nodes in dependency order (Kahn); nodes on a cycle come back separately."""
    nodes = [n for n in tree.nodes if isinstance(n, FairlinesNode)]
    deps = {n.name: set() for n in nodes}
    for n in nodes:
        for sock in n.inputs:
            src = _source(sock, links)
            if src is not None and src.node.name in deps:
                deps[n.name].add(src.node.name)
    by_name = {n.name: n for n in nodes}
    order, done = [], set()
    remaining = dict(deps)
    while remaining:
        ready = [name for name, d in remaining.items() if d <= done]
        if not ready:
            break
        for name in sorted(ready):
            order.append(by_name[name])
            done.add(name)
            del remaining[name]
    return order, [by_name[name] for name in remaining]


def _show(node, state, message, ms, info=None):
    # Writing the same value again still tags a redraw; skip unchanged properties.
    if node.fl_state != state:
        node.fl_state = state
    if node.fl_message != message:
        node.fl_message = message
    node.fl_time_ms = ms
    if info is not None and node.fl_info != info:
        node.fl_info = info
    if state == "ERROR":
        node.use_custom_color = True
        node.color = ERROR_COLOUR
    elif node.use_custom_color and _is_error_colour(node.color):
        node.use_custom_color = False  # only undo our own red, never a colour the user chose


def _is_error_colour(colour):
    # Stored in single precision (and as RGBA in newer releases): compare loosely.
    return all(abs(a - b) < 1e-3 for a, b in zip(colour, ERROR_COLOUR))


def _message(exc):
    # Our own messages read as sentences; engine exceptions keep their class name
    # (InvalidInput, InfeasibleFormParameters, ...) because it says what kind of problem it is.
    if isinstance(exc, (NodeError, engine.EngineMissing)):
        return str(exc)
    return "%s: %s" % (type(exc).__name__, exc)


def evaluate(tree, deadline=None):
    """Evaluate a tree; returns the names of the nodes that ran. With a deadline
    (perf_counter seconds) it stops between nodes once past it and queues the tree again."""
    if queue.busy:
        return []
    queue.busy = True
    t_start = time.perf_counter()
    ran = []
    try:
        if not tree.use_fake_user:
            # A node tree shown in an editor has no real user, and Blender drops data without
            # users when saving: the design would vanish from the .blend.
            tree.use_fake_user = True
        links = _link_map(tree)
        order, cyclic = _order(tree, links)
        for node in cyclic:
            _show(node, "ERROR", "Node is part of a cycle; links must flow one way", -1.0)
            _cache.pop((tree.name, node.name), None)
        for node in order:
            if deadline is not None and ran and time.perf_counter() > deadline:
                _pending.add(tree.name)  # resumed by the timer at its next tick
                break
            if _run_node(tree, node, links):
                ran.append(node.name)
        live = {n.name for n in tree.nodes}
        trees = set(bpy.data.node_groups.keys())
        for key in [k for k in _cache if (k[0] == tree.name and k[1] not in live) or k[0] not in trees]:
            del _cache[key]  # deleted nodes, and trees deleted or renamed
    finally:
        queue.busy = False
    last_stats.update(tree=tree.name, evaluated=ran, ms=(time.perf_counter() - t_start) * 1e3)
    return ran


def _gather_inputs(tree, node, links):
    """The node's input values (from the upstream cache or its own sockets), the parts of its
    cache key, the name of an upstream node that blocks it (failed or not run) and the message
    of an incompatible link (None when there is none)."""
    inputs, key_parts, blocked, bad = {}, [], None, None
    for sock in node.inputs:
        if not sock.enabled:
            continue
        src = _source(sock, links)
        if src is not None:
            if not compatible(src.bl_idname, sock.bl_idname):
                bad = "Cannot connect %s '%s' to %s input '%s'" % (
                    src.bl_label, src.name, sock.bl_label, sock.name)
                continue
            up = _cache.get((tree.name, src.node.name))
            if up is not None and up.later is not None and src.name not in up.outputs:
                _finish(tree, src.node, up)  # this output is needed now: do the deferred part
            if up is None or not up.ok:
                blocked = src.node.name
                continue
            inputs[sock.name] = up.outputs.get(src.name)
            key_parts.append((sock.name, src.node.name, src.name, up.version))
        else:
            value = sock.value() if hasattr(sock, "value") else None
            inputs[sock.name] = value
            key_parts.append((sock.name, value))
    return inputs, key_parts, blocked, bad


def _compute(node, inputs, entry):
    """(outputs, ok, message, ms) of node.compute: engine errors and anything else become the
    node's message, never raised. A node that was slow last time says it is working."""
    t0 = time.perf_counter()
    slow = entry is not None and entry.ms > progress.SLOW_MS
    if slow:
        progress.status("Fairlines: %s (about %.1f s) ..." % (node.name, entry.ms * 1e-3))
    try:
        outputs = node.compute(inputs) or {}
        ok, message = True, ""
    except Exception as exc:
        outputs, ok, message = {}, False, _message(exc)
    if slow:
        progress.status(None)
    return outputs, ok, message, (time.perf_counter() - t0) * 1e3


def _run_node(tree, node, links):
    """Runs the node unless its cache entry holds the same inputs; True when it ran (or was
    shown blocked or wrongly linked)."""
    ckey = (tree.name, node.name)
    entry = _cache.get(ckey)
    inputs, key_parts, blocked, bad = _gather_inputs(tree, node, links)
    try:
        sig = node.signature()
    except Exception as exc:
        sig = ("unreadable", str(exc))
    key = (node.bl_idname, sig, tuple(key_parts), bad, blocked)
    if entry is not None and entry.key == key and not (entry.ok and node.needs_run()):
        return False
    version = entry.version + 1 if entry is not None else 1
    if bad is not None or blocked is not None:
        if bad is not None:
            _show(node, "ERROR", bad, -1.0)
        else:
            _show(node, "BLOCKED", "Waiting for '%s'" % blocked, -1.0)
        _cache[ckey] = Entry(key, {}, version, -1.0, False)
        return True
    outputs, ok, message, ms = _compute(node, inputs, entry)
    info = outputs.pop("__info__", "") if ok else None
    later = outputs.pop("__later__", None) if ok else None
    # With a deferred job the node keeps showing its previous info until the job completes it
    # (a shorter info for one redraw would make the node jump in size on every slider step).
    _show(node, "OK" if ok else "ERROR", message, ms, info if later is None else None)
    _cache[ckey] = Entry(key, outputs, version, ms, ok, later, info or "")
    if later is not None:
        _deferred.append(ckey)
    return True
