"""The queue of trees waiting for evaluation.

Property update callbacks (props), a tree's update() and scripts push the tree here; the
evaluator drains it from its timer. This module imports only ids, so the modules that push
(props, sockets, the nodes) do not depend on the evaluator, and the add-on's imports stay
acyclic (tests/python/test_addon_import_graph.py).
"""

from . import ids

pending = set()  # names of trees waiting for evaluation
# True while the evaluator runs: the properties it writes itself (node status) queue nothing.
busy = False
_wake = None     # set by the evaluator: makes sure its timer will run


def is_fairlines_tree(tree):
    return tree is not None and getattr(tree, "bl_idname", "") == ids.TREE


def push(tree):
    """Queue a tree for evaluation (a zero-delay timer evaluates it, once per burst)."""
    if busy or not is_fairlines_tree(tree):
        return
    pending.add(tree.name)
    if _wake is not None:
        _wake()


def set_waker(wake):
    """Install the callable that starts the evaluation timer (the evaluator does, on import)."""
    global _wake
    _wake = wake
