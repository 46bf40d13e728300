"""Shared switch for the gallery: ``KREISEL_QUICK=1`` shrinks problem sizes for the tests."""

import os

QUICK = os.environ.get("KREISEL_QUICK", "") not in ("", "0")


def size(full, quick):
    """``quick`` when running under the test suite, else ``full``."""
    return quick if QUICK else full
