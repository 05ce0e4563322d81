# SPDX-License-Identifier: MIT
"""The end every tests/tools check script shares: its failures printed, a summary line, the exit status."""


def finish(what: str, failures) -> int:
    """Prints "FAIL: <failure>" for each, then "<what>: OK" or "<what>: N failure(s)"; returns the
    exit status (1 when anything failed, else 0)."""
    for f in failures:
        print("FAIL:", f)
    print(f"{what}: {'OK' if not failures else f'{len(failures)} failure(s)'}")
    return 1 if failures else 0
