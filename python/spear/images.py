"""Camera images as pictures: uint8 RGB (H, W, 3) arrays for a PNG writer or a notebook.

    import spear.images
    Image.fromarray(spear.images.id_colours(pixels["object_ids"])).save("ids.png")
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

__all__ = ["depth_grey", "id_colours"]


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
