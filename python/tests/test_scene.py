"""Scenes from dicts, JSON text and files: core's reader, core's messages, Python exceptions."""
import json
import math
import os

import numpy as np
import pytest

import refract
from conftest import sphere_scene


def test_a_dict_scene_reads_like_its_file(tmp_path):
    d = sphere_scene()
    p = tmp_path / "s.json"
    p.write_text(json.dumps(d))
    a, b, c = refract.scene(d), refract.scene(str(p)), refract.scene(json.dumps(d))
    assert (a.width, a.height) == (32, 24)
    assert a.objects == b.objects == c.objects == ["ball", "floor"]
    assert b.source == str(p)
    assert np.array_equal(refract.render(a).rgb, refract.render(b).rgb)


def test_a_malformed_field_raises_valueerror_naming_the_field():
    d = sphere_scene()
    d["objects"][0]["radius"] = "one"
    with pytest.raises(ValueError) as e:
        refract.scene(d, name="mine")
    assert str(e.value).startswith("mine: /objects/0/radius: ")
    assert isinstance(e.value, refract.InputError)


def test_a_nan_in_a_dict_is_refused_by_the_reader_with_its_path():
    d = sphere_scene()
    d["objects"][0]["radius"] = math.nan
    with pytest.raises(refract.InputError, match=r"^scene: /objects/0/radius: must be a finite number"):
        refract.scene(d)


def test_numpy_values_are_accepted_in_dicts():
    d = sphere_scene()
    d["objects"][0]["center"] = np.array([0.0, 1.0, 0.0])
    d["objects"][0]["radius"] = np.float32(1.0)
    d["camera"]["width"] = np.int64(32)
    assert refract.scene(d).width == 32


def test_malformed_json_text_and_a_missing_file_raise_one_line_errors(tmp_path):
    with pytest.raises(refract.InputError, match="^scene: malformed JSON: "):
        refract.scene('{"camera": ')
    missing = str(tmp_path / "none.json")
    with pytest.raises(refract.InputError, match="none.json: cannot open scene file"):
        refract.scene(missing)
    with pytest.raises(TypeError):
        refract.scene(42)


def test_an_unknown_top_level_field_is_refused():
    d = sphere_scene()
    d["cameras"] = {}
    with pytest.raises(refract.InputError, match="cameras"):
        refract.scene(d)


def test_the_example_scenes_load(source_dir):
    s = refract.scene(os.path.join(source_dir, "scenes", "examples", "ohtsuka1998-diamond.json"))
    assert (s.width, s.height) == (640, 480)
    assert s.spectral and s.polarisation == "natural"
    assert "diamond" in s.objects


def test_a_self_referencing_or_absurdly_nested_dict_raises_instead_of_crashing():
    d = sphere_scene()
    d["description"] = d  # a cycle
    with pytest.raises(refract.InputError, match="nested more than 64 levels"):
        refract.scene(d)
    deep = []
    for _ in range(10000):
        deep = [deep]
    d = sphere_scene()
    d["description"] = deep
    with pytest.raises(refract.InputError, match="/description/0/0"):
        refract.scene(d)


def test_a_value_json_cannot_hold_is_named():
    d = sphere_scene()
    d["objects"][0]["radius"] = object()
    with pytest.raises(refract.InputError, match="/objects/0/radius: cannot be written in JSON"):
        refract.scene(d)
