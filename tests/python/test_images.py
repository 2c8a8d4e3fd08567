"""spear.images: camera images as uint8 RGB pictures."""

from __future__ import annotations

import numpy as np

import spear.images


def test_id_colours_are_stable_distinct_and_black_for_background() -> None:
    ids = np.array([[0, 1, 2], [2, 1, 0x00FFFFFF]], dtype=np.uint32)
    rgb = spear.images.id_colours(ids)
    assert rgb.shape == (2, 3, 3) and rgb.dtype == np.uint8
    assert (rgb[0, 0] == 0).all() and (rgb[1, 2] != 0).any()
    assert (rgb[0, 1] == rgb[1, 1]).all() and (rgb[0, 2] == rgb[1, 0]).all()  # an id's colour is fixed
    assert (rgb[0, 1] != rgb[0, 2]).any()  # neighbouring ids differ
    assert (rgb[ids != 0] >= 96).all()  # an object is never drawn near black, whatever its id
    assert (spear.images.id_colours(np.array([[1]], dtype=np.uint32)) == rgb[0, 1]).all()  # same id, same colour


def test_depth_grey_is_brightest_near_and_black_for_background() -> None:
    depth = np.array([[0.0, 1.0, 2.0, 3.0]], dtype=np.float32)
    rgb = spear.images.depth_grey(depth)
    assert rgb.shape == (1, 4, 3) and rgb.dtype == np.uint8
    level = rgb[0, :, 0]
    assert level[0] == 0 and level[1] == 255 and level[1] > level[2] > level[3] > 0
    assert (rgb[..., 0] == rgb[..., 1]).all() and (rgb[..., 1] == rgb[..., 2]).all()
    assert (spear.images.depth_grey(np.zeros((2, 2), dtype=np.float32)) == 0).all()
