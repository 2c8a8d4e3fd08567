"""Camera images as pictures: uint8 RGB (H, W, 3) arrays for a PNG writer or a notebook; and the EXR files
the render queue writes, read back as the arrays read_pixels() returns.

    import spear.images
    Image.fromarray(spear.images.id_colours(pixels["object_ids"])).save("ids.png")
    depth = spear.images.read_exr("out/depth/0000.exr")   # float32 (H, W), as pixels["depth"]
"""

from __future__ import annotations

import importlib
import os
from typing import Any

import numpy as np
from numpy.typing import NDArray

__all__ = ["depth_grey", "id_colours", "read_exr"]


def read_exr(path: str | os.PathLike[str]) -> NDArray[Any]:
    """The image of an OpenEXR file (through the engine's OpenEXR library): (H, W) for one channel, else
    (H, W, C) in R, G, B, A order, as float16, float32 or uint32 as stored, so a file the render queue wrote
    equals the read_pixels() array it came from. Raises spear.errors.NotFoundError for a missing file and
    InvalidArgumentError for one that is not EXR."""
    engine = importlib.import_module("spear._spear_engine")  # the reader is C++, in the engine library
    image: NDArray[Any] = engine._read_exr(os.fspath(path))
    return image


def id_colours(ids: NDArray[np.uint32]) -> NDArray[np.uint8]:
    """Each id in its own colour (object_ids, material_ids), 0 (background) black. The colour is a fixed
    hash of the id, so an object keeps its colour from frame to frame and image to image."""
    h = ids.astype(np.uint64) * np.uint64(2654435761) % np.uint64(2**32)
    channels = [(h >> np.uint64(s)) & np.uint64(255) for s in (0, 8, 16)]
    rgb: NDArray[np.uint8] = (np.stack(channels, axis=-1) // 2 + 96).astype(np.uint8)  # never near black
    rgb[ids == 0] = 0
    return rgb


def depth_grey(depth: NDArray[np.float32]) -> NDArray[np.uint8]:
    """Depth in grey, the nearest surface white and the farthest dark; background (0) black."""
    valid = depth > 0
    if not valid.any():
        return np.zeros((*depth.shape, 3), dtype=np.uint8)
    near, far = float(depth[valid].min()), float(depth[valid].max())
    level = np.clip(1.0 - (depth - near) / max(far - near, 1e-6), 0.0, 1.0) * 215 + 40
    grey = np.where(valid, level, 0.0).astype(np.uint8)
    return np.repeat(grey[..., None], 3, axis=2)
