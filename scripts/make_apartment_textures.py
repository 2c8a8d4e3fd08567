"""Writes assets/textures/*.png, the default scene's PBR textures, from seeded noise: nothing is downloaded, so
the textures are the project's own (CC0, see assets/textures/README.md) and can be made again exactly.

Every texture tiles (its noise is periodic, made by filtering white noise in the frequency domain), and each
material has up to three maps in the glTF layout the renderers read (core/sensors/material_library.h):
  *_color.png   sRGB base colour (the material's BaseColor factor is white: the map is the albedo),
  *_rm.png      linear, R = ambient occlusion, G = roughness, B = metallic (multiplying the AmbientOcclusion,
                Roughness and Metallic factors; the scene names the file as both RoughnessMetallicTexture and
                OcclusionTexture, glTF's and UE's ORM packing),
  *_normal.png  tangent-space normal map, OpenGL convention (green up), from a height field.
Materials repeat them every FMaterialDesc.TextureSize metres (scripts/make_apartment_scene.py).

    /usr/bin/python3 scripts/make_apartment_textures.py          # write the maps
    /usr/bin/python3 scripts/make_apartment_textures.py --check  # exit 1 if a committed map differs
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable
from pathlib import Path

import numpy as np
from numpy.typing import NDArray
from PIL import Image  # type: ignore[import]  # Debian ships no Pillow stubs

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "assets" / "textures"
Array = NDArray[np.float64]


def frequencies(n: int) -> Array:
    """np.fft.fftfreq(n): the cycles per sample of each term of an n-point transform."""
    k = np.arange(n)
    out: Array = np.where(k < (n + 1) // 2, k, k - n) / n
    return out


def periodic_noise(rng: np.random.Generator, shape: tuple[int, int], scale: tuple[float, float]) -> Array:
    """Gaussian noise low-passed to features of about `scale` pixels (rows, columns), zero mean, unit variance.
    Filtering in the frequency domain makes it periodic, so the texture tiles without a seam."""
    white = rng.standard_normal(shape)
    fy = frequencies(shape[0])[:, None] * scale[0]
    fx = frequencies(shape[1])[None, :] * scale[1]
    smooth: Array = np.fft.ifft2(np.fft.fft2(white) * np.exp(-(fx**2 + fy**2) * 4.0)).real
    out: Array = (smooth - smooth.mean()) / max(float(smooth.std()), 1e-12)
    return out


def srgb(linear: Array) -> NDArray[np.uint8]:
    c = np.clip(linear, 0.0, 1.0)
    encoded = np.where(c <= 0.0031308, 12.92 * c, 1.055 * np.power(c, 1.0 / 2.4) - 0.055)
    out: NDArray[np.uint8] = np.round(encoded * 255.0).astype(np.uint8)
    return out


def unorm(values: Array) -> NDArray[np.uint8]:
    out: NDArray[np.uint8] = np.round(np.clip(values, 0.0, 1.0) * 255.0).astype(np.uint8)
    return out


def normal_map(height: Array, strength: float) -> NDArray[np.uint8]:
    """Tangent-space normals of a height field (in pixels of height per pixel x `strength`), wrapping at the
    edges. u runs along columns and v down the rows; green points up the image, i.e. towards -v."""
    dx = (np.roll(height, -1, axis=1) - np.roll(height, 1, axis=1)) * 0.5 * strength
    dy = (np.roll(height, -1, axis=0) - np.roll(height, 1, axis=0)) * 0.5 * strength
    n = np.stack([-dx, dy, np.ones_like(height)], axis=-1)
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    return unorm(n * 0.5 + 0.5)


def occlusion(height: Array, radius: float, strength: float) -> Array:
    """Ambient occlusion of a height field (pixels of height), as a cavity map: how far each texel lies below
    the mean height of its surroundings (a periodic Gaussian of `radius` pixels), exp(-strength x depth). A
    groove or the grout between tiles sees less of the sky than the faces beside it; a bump sees all of it."""
    fy = frequencies(height.shape[0])[:, None]
    fx = frequencies(height.shape[1])[None, :]
    gaussian = np.exp(-2.0 * (np.pi * radius) ** 2 * (fx**2 + fy**2))
    mean = np.fft.ifft2(np.fft.fft2(height) * gaussian).real
    out: Array = np.exp(-strength * np.maximum(mean - height, 0.0))
    return out


def rm_map(roughness: Array, ao: Array, metallic: float = 0.0) -> NDArray[np.uint8]:
    return unorm(np.stack([ao, roughness, np.full_like(roughness, metallic)], axis=-1))


def groove(distance: Array, width: float) -> Array:
    """1 inside a groove `width` pixels wide around distance 0, easing to 0 at its edges."""
    return np.clip(1.0 - np.abs(distance) / (width / 2.0), 0.0, 1.0) ** 0.5


def wood_floor(rng: np.random.Generator) -> dict[str, NDArray[np.uint8]]:
    """Oak-like planks: 8 across one repeat, ends staggered, each plank its own tint and grain."""
    size, planks = 512, 8
    y, x = np.mgrid[0:size, 0:size].astype(np.float64)
    width = size / planks
    plank = (y // width).astype(int)
    # Two boards per row of planks per repeat, their joints staggered row by row.
    offsets = rng.uniform(0, size, planks)
    along = (x + offsets[plank]) % size
    length = size / 2
    joint = along % length
    piece = plank * 2 + (along // length).astype(int)
    tints = rng.normal(0.0, 1.0, planks * 2)[piece]
    # Grain: noise stretched along the plank, its rings bent by a slower noise.
    grain = periodic_noise(rng, (size, size), (6.0, 90.0))
    figure = periodic_noise(rng, (size, size), (30.0, 200.0))
    rings = np.sin((y + 12.0 * figure) * (2 * np.pi / 9.0) + 3.0 * grain) * 0.5 + 0.5
    darkness = 0.72 + 0.1 * tints + 0.06 * grain + 0.16 * rings
    seam_rows = np.maximum(groove(y % width, 3.0), groove(y % width - width, 3.0))
    seam_ends = np.maximum(groove(joint, 3.0), groove(joint - length, 3.0))
    seams = np.maximum(seam_rows, seam_ends)
    base = np.array([0.42, 0.24, 0.11])  # linear albedo of a mid oak
    color = base[None, None, :] * darkness[..., None] * (1.0 - 0.6 * seams[..., None])
    roughness = np.clip(0.5 + 0.08 * grain + 0.1 * rings + 0.35 * seams, 0.0, 1.0)
    height = -2.0 * seams + 0.15 * rings
    return {"color": srgb(color), "rm": rm_map(roughness, occlusion(height, 4.0, 0.35)),
            "normal": normal_map(height, 1.0)}


def plaster(rng: np.random.Generator) -> dict[str, NDArray[np.uint8]]:
    """Painted plaster: a faint mottle in the colour and a fine trowelled relief in the normals."""
    size = 256
    mottle = periodic_noise(rng, (size, size), (60.0, 60.0))
    fine = periodic_noise(rng, (size, size), (3.0, 3.0))
    strokes = periodic_noise(rng, (size, size), (12.0, 40.0))
    base = np.array([0.8, 0.78, 0.73])
    color = base[None, None, :] * (1.0 + 0.012 * mottle + 0.01 * fine)[..., None]
    # Fine relief only: a slope that lasts over many texels turns a whole patch to or from the light, which
    # reads as stains, not as texture.
    height = 0.6 * fine + 0.15 * strokes
    return {"color": srgb(color), "normal": normal_map(height, 0.3)}


def fabric(rng: np.random.Generator) -> dict[str, NDArray[np.uint8]]:
    """A plain weave of 32 threads each way per repeat, its yarns slightly uneven."""
    size, threads = 256, 32
    y, x = np.mgrid[0:size, 0:size].astype(np.float64)
    period = size / threads
    warp = np.sin(x * np.pi / period) ** 2  # across each vertical thread
    weft = np.sin(y * np.pi / period) ** 2
    over = ((x // period + y // period) % 2).astype(np.float64)  # which thread lies on top
    profile_w = np.sin(((y % (2 * period)) / (2 * period)) * np.pi)
    profile_h = np.sin(((x % (2 * period)) / (2 * period)) * np.pi)
    height = over * warp * (0.5 + 0.5 * profile_w) + (1 - over) * weft * (0.5 + 0.5 * profile_h)
    slub = periodic_noise(rng, (size, size), (2.0, 40.0)) * 0.5 + periodic_noise(rng, (size, size), (40.0, 2.0)) * 0.5
    base = np.array([0.16, 0.25, 0.4])
    color = base[None, None, :] * (0.8 + 0.3 * height + 0.06 * slub)[..., None]
    roughness = np.clip(0.92 + 0.05 * slub, 0.0, 1.0)
    return {"color": srgb(color), "rm": rm_map(roughness, occlusion(height * 3.0, 3.0, 0.25)),
            "normal": normal_map(height * 3.0, 0.5)}


def ceramic_tile(rng: np.random.Generator) -> dict[str, NDArray[np.uint8]]:
    """Glazed tiles, 4 x 4 per repeat, in grout; each tile's glaze a little different."""
    size, tiles = 512, 4
    y, x = np.mgrid[0:size, 0:size].astype(np.float64)
    pitch = size / tiles
    tile = (y // pitch).astype(int) * tiles + (x // pitch).astype(int)
    gx, gy = x % pitch, y % pitch
    edge = np.minimum(np.minimum(gx, pitch - gx), np.minimum(gy, pitch - gy))  # pixels to the tile's edge
    grout = np.clip(1.0 - (edge - 3.0) / 2.0, 0.0, 1.0)  # 6 px of grout, a 2 px bevel into it
    bevel = np.clip(edge / 10.0, 0.0, 1.0)  # the glaze rounds over its last 10 px
    glaze = rng.normal(0.0, 1.0, tiles * tiles)[tile]
    cloud = periodic_noise(rng, (size, size), (40.0, 40.0))
    base = np.array([0.55, 0.62, 0.6])
    grout_colour = np.array([0.45, 0.44, 0.42])
    tile_colour = base[None, None, :] * (1.0 + 0.04 * glaze + 0.02 * cloud)[..., None]
    color = tile_colour * (1 - grout[..., None]) + grout_colour[None, None, :] * grout[..., None]
    roughness = 0.12 + 0.73 * grout
    height = 3.0 * np.sqrt(bevel) * (1 - grout) - 1.0 * grout
    return {"color": srgb(color), "rm": rm_map(roughness, occlusion(height, 4.0, 0.35)),
            "normal": normal_map(height, 1.0)}


MATERIALS: dict[str, Callable[[np.random.Generator], dict[str, NDArray[np.uint8]]]] = {
    "wood_floor": wood_floor,
    "plaster": plaster,
    "fabric": fabric,
    "ceramic_tile": ceramic_tile,
}


def maps() -> dict[str, NDArray[np.uint8]]:
    """Every map by file name, each material from its own seed so that one can change alone."""
    out: dict[str, NDArray[np.uint8]] = {}
    for seed, (name, make) in enumerate(MATERIALS.items()):
        for kind, pixels in make(np.random.default_rng(1000 + seed)).items():
            out[f"{name}_{kind}.png"] = pixels
    return out


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="compare the committed maps instead of writing")
    args = parser.parse_args()
    stale = []
    for name, pixels in maps().items():
        path = OUT / name
        if args.check:
            if not path.exists() or not np.array_equal(np.asarray(Image.open(path).convert("RGB")), pixels):
                stale.append(name)
            continue
        OUT.mkdir(parents=True, exist_ok=True)
        Image.fromarray(pixels, "RGB").save(path, optimize=True)
        print(f"wrote {path.relative_to(ROOT)} ({path.stat().st_size // 1024} KiB)")
    if stale:
        print("stale (run scripts/make_apartment_textures.py): " + ", ".join(stale), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
