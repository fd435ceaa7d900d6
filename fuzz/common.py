"""Shared parts of the fuzz harnesses (atheris, coverage-guided).

Each harness feeds the bytes libFuzzer mutates to one reader or entry point of the package.
The contract under test: whatever the input, the call returns normally or raises one of the
documented exceptions (``fl.InvalidInput`` and its subclass ``fl.InfeasibleFormParameters``;
``fl.ConvergenceError`` where a solver is involved). Any other exception, a crash or a hang is
a finding: libFuzzer stops and writes the input to ``build/fuzz/crash-*``.
"""

import os
import pathlib
import sys
import tempfile

import atheris

with atheris.instrument_imports():
    import fairlines as fl

EXPECTED = (fl.InvalidInput,)

# Principal dimensions a harness picks from with the first byte of its input: sensible ones,
# and the bad values every reader must refuse by name.
DIMENSIONS = [
    (100.0, 16.0, 6.0), (121.92, 18.757, 7.503), (230.0, 32.2, 10.8), (1.0, 0.2, 0.05),
    (0.0, 16.0, 6.0), (-100.0, 16.0, 6.0), (float("nan"), 16.0, 6.0), (1e300, 16.0, 6.0),
    (100.0, float("inf"), 6.0), (100.0, 16.0, 0.0), (1e-300, 1e-300, 1e-300), ("100", None, 6.0),
]

_SCRATCH = pathlib.Path(tempfile.mkdtemp(prefix="fairlines-fuzz-", dir="/dev/shm" if os.path.isdir("/dev/shm") else None))


def scratch_file(data: bytes, name: str = "input") -> pathlib.Path:
    """The bytes written to a file in a private scratch folder (readers take paths)."""
    path = _SCRATCH / name
    path.write_bytes(data)
    return path


def dimensions(data: bytes):
    """(lpp, beam, draft) chosen by the first byte, and the rest of the input."""
    if not data:
        return DIMENSIONS[0], b""
    return DIMENSIONS[data[0] % len(DIMENSIONS)], data[1:]


def main(test_one_input):
    """Run one harness under libFuzzer (arguments as for any libFuzzer binary). argv[0] is the
    interpreter and the script, so that libFuzzer's -merge=1 can start the harness again."""
    argv0 = f"{sys.executable} {os.path.abspath(sys.argv[0])}"
    atheris.Setup([argv0] + sys.argv[1:], test_one_input)
    atheris.Fuzz()
