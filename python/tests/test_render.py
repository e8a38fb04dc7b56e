"""`scratchwave.render(scene)`: a NumPy image; regions equal the parts of the whole image bit
for bit; the same render through the CLI reader (a scene file path) and a dict."""

import json
from pathlib import Path

import numpy as np
import pytest

import scratchwave as sw

ROOT = Path(__file__).resolve().parents[2]
SCENE = ROOT / "conformance/scenes/velinov_footprint.json"


def test_render_file_dict_and_regions():
    img, stats = sw.render(SCENE, return_stats=True)
    cam = json.loads(SCENE.read_text())["camera"]
    assert img.shape == (cam["height_px"], cam["width_px"], 3) and img.dtype == np.float32
    assert img.max() > 0 and np.isfinite(img).all()
    assert stats["primary_rays"] >= img.shape[0] * img.shape[1]
    same = sw.render(json.loads(SCENE.read_text()), base_dir=SCENE.parent)
    np.testing.assert_array_equal(img.view(np.uint32), same.view(np.uint32))
    part = sw.render(SCENE, region=(5, 3, 20, 11))
    np.testing.assert_array_equal(part.view(np.uint32), img[3:14, 5:25].view(np.uint32))


def test_render_errors_name_the_field():
    scene = json.loads(SCENE.read_text())
    scene["camera"]["width_px"] = 0
    with pytest.raises(sw.InputError, match=r"camera\.width_px"):
        sw.render(scene, base_dir=SCENE.parent)
    with pytest.raises(sw.InputError, match="region"):
        sw.render(SCENE, region=(60, 0, 10, 10))
    with pytest.raises(ValueError, match="backend"):
        sw.render(SCENE, backend="spirv")
