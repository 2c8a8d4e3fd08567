"""A typed SPFUNCTION's TypedDict result keeps its Python type's promise on both transports: a complete
TypedDict has every key, a partial one only what was produced, and a C++ function that forgets a field of
a complete result gets a clear error naming the struct and the field, while the engine keeps running.
The functions live in tests/python/result_plugin, built out of tree like any plugin."""

from __future__ import annotations

import sys
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import spear

sys.path.insert(0, str(Path(__file__).resolve().parent))
from plugin_build import build_importable_plugin  # noqa: E402

SOURCE = Path(__file__).resolve().parent / "result_plugin"
SAMPLES = np.array([2.0, 1.0, 2.0, 3.0, 2.0], dtype=np.float32)


@pytest.fixture(scope="session")
def result_plugin_dir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return build_importable_plugin(SOURCE, tmp_path_factory)


@pytest.fixture
def measurer(instance: spear.Instance, result_plugin_dir: Path) -> Iterator[Any]:
    instance.load_plugin(result_plugin_dir / "result_plugin")
    with instance.begin_frame():
        yield instance.get_game().spawn_actor(uclass="AMeasurer")
    with instance.end_frame():
        pass


def test_complete_typed_dict_has_every_key(measurer: Any) -> None:
    result = measurer.Measure(Samples=SAMPLES)
    assert sorted(result) == ["Counts", "Values"]
    assert result["Values"].tolist() == [1.0, 2.0, 3.0] and result["Values"].dtype == np.float32
    assert result["Counts"].tolist() == [1, 3, 1] and result["Counts"].dtype == np.int64


def test_partial_typed_dict_has_only_what_was_produced(measurer: Any) -> None:
    assert sorted(measurer.MeasureSome(Samples=SAMPLES, bCount=True)) == ["Counts", "Values"]
    assert sorted(measurer.MeasureSome(Samples=SAMPLES, bCount=False)) == ["Values"]


def test_a_forgotten_field_is_reported_and_the_engine_keeps_running(measurer: Any) -> None:
    forgotten = r"^AMeasurer\.MeasureForgetful\(\): FMeasurement\.Counts was not set"
    with pytest.raises(spear.InvalidStateError, match=forgotten):
        measurer.MeasureForgetful(Samples=SAMPLES)
    assert measurer.Measure(Samples=SAMPLES)["Counts"].tolist() == [1, 3, 1]


def test_a_complete_typed_dict_property_without_its_arrays_is_reported(measurer: Any) -> None:
    with pytest.raises(spear.InvalidStateError, match=r"FMeasurement\.Values was not set"):
        measurer.Unset
    assert measurer.Measure(Samples=SAMPLES)["Values"].tolist() == [1.0, 2.0, 3.0]


def test_generated_stubs_say_which_keys_are_promised(result_plugin_dir: Path) -> None:
    stub = (result_plugin_dir / "result_plugin/api.pyi").read_text()
    assert "class FMeasurement(TypedDict):" in stub
    assert "class FPartialMeasurement(TypedDict, total=False):" in stub
