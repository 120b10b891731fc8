"""What the module tests share: scripts/benchmark_report.py loaded as a module (scripts/ is not a
package), for the benchmark tests that feed it synthetic results."""
import importlib.util
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]


@pytest.fixture
def benchmark_report():
    spec = importlib.util.spec_from_file_location("benchmark_report",
                                                  REPO / "scripts" / "benchmark_report.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod
