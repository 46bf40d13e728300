import pytest

from kreisel.tour import SECTIONS


@pytest.fixture(scope="session")
def sections():
    """Every section of the tour, run once (quick problems)."""
    return [function(True) for function in SECTIONS]
