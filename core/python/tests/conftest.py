"""What the module tests share: load_module, which imports a module of the repository without its
package's __init__ (the add-on's imports bpy; scripts/ is not a package), scripts/
benchmark_report.py loaded with it, for the benchmark tests that feed it synthetic results, and
case_table, the shader ops' tables of cases that the core's tests check too."""
import importlib
import json
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]
ADDON = REPO / "python_addon" / "torrance"
CASE_TABLES = REPO / "core" / "tests" / "data"


@pytest.fixture(scope="session")
def load_module():
    """load(name, folder=the add-on's folder): the module `name` ("shader_graph.noise",
    "matrices", "benchmark_report") imported with `folder` first on sys.path for the import only,
    so the add-on's modules come without its __init__ and keep their relative imports."""
    def load(name, folder=ADDON):
        sys.path.insert(0, str(folder))
        try:
            return importlib.import_module(name)
        finally:
            sys.path.remove(str(folder))
    return load


@pytest.fixture
def benchmark_report(load_module):
    return load_module("benchmark_report", REPO / "scripts")


@pytest.fixture(scope="session")
def case_table():
    """read(family): core/tests/data/shader_<family>_cases.json, parsed."""
    def read(family):
        return json.loads((CASE_TABLES / f"shader_{family}_cases.json").read_text())
    return read
