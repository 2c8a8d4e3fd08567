// How each camera modality is shown: as RGBA bytes for a canvas. Colour images as they are (HDR ones clamped
// and gamma-encoded), ids in colours from a hash (neighbours differ), depth in a false-colour ramp over the
// image's own range, vectors (normals, positions) mapped to RGB. The mapping is simple on purpose: the tests
// recompute it from read_pixels() and compare the canvas with it.

import type { NDArray } from "./spear/client.js";

/** An IEEE half (float16) from its 16 bits. */
export function halfToFloat(bits: number): number {
  const sign = bits & 0x8000 ? -1 : 1;
  const exponent = (bits >> 10) & 0x1f;
  const fraction = bits & 0x3ff;
  if (exponent === 0) return sign * fraction * 2 ** -24;
  if (exponent === 31) return fraction ? NaN : sign * Infinity;
  return sign * (1 + fraction / 1024) * 2 ** (exponent - 15);
}

/** The colour of an object or material id: 0 (nothing) black, any other a hash's bytes. */
export function idColor(id: number): [number, number, number] {
  if (id === 0) return [0, 0, 0];
  const hash = Math.imul(id, 2654435761) >>> 0; // Knuth's multiplicative hash
  return [hash & 0xff, (hash >>> 8) & 0xff, (hash >>> 16) & 0xff];
}

/** A dark-blue to yellow ramp for t in [0, 1] (linear pieces through five stops). */
export function ramp(t: number): [number, number, number] {
  const stops: [number, number, number][] = [[13, 8, 135], [84, 2, 163], [185, 50, 137], [249, 142, 9], [240, 249, 33]];
  const x = Math.min(Math.max(t, 0), 1) * (stops.length - 1);
  const i = Math.min(Math.floor(x), stops.length - 2);
  const f = x - i;
  const a = stops[i]!;
  const b = stops[i + 1]!;
  return [Math.round(a[0] + (b[0] - a[0]) * f), Math.round(a[1] + (b[1] - a[1]) * f), Math.round(a[2] + (b[2] - a[2]) * f)];
}

function values(array: NDArray): ArrayLike<number> {
  if (array.dtype === "float16") {
    const bits = array.data as Uint16Array;
    const out = new Float32Array(bits.length);
    for (let i = 0; i < bits.length; ++i) out[i] = halfToFloat(bits[i]!);
    return out;
  }
  return array.data as unknown as ArrayLike<number>;
}

/** The image of one modality's array ((H, W) or (H, W, C)) as RGBA bytes, and its width and height. */
export function toRgba(modality: string, array: NDArray): ImageData {
  const [height = 0, width = 0, channels = 1] = array.shape;
  const image = new ImageData(Math.max(width, 1), Math.max(height, 1));
  const out = image.data;
  const v = values(array);
  const count = width * height;
  const put = (i: number, r: number, g: number, b: number) => {
    out[4 * i] = r;
    out[4 * i + 1] = g;
    out[4 * i + 2] = b;
    out[4 * i + 3] = 255;
  };
  if (modality === "final_color" && array.dtype === "uint8" && channels === 4) {
    // Already RGBA bytes: one copy, made opaque (a camera may write coverage into alpha).
    out.set(array.bytes.subarray(0, 4 * count));
    for (let i = 3; i < out.length; i += 4) out[i] = 255;
  } else if (modality === "final_color" && array.dtype === "uint8") {
    for (let i = 0; i < count; ++i) put(i, v[i * channels]!, v[i * channels + 1]!, v[i * channels + 2]!);
  } else if (modality === "object_ids" || modality === "material_ids") {
    for (let i = 0; i < count; ++i) put(i, ...idColor(v[i]!));
  } else if (channels === 1) {
    // Depth and the scalar material inputs: a ramp over the finite values' range.
    let lo = Infinity;
    let hi = -Infinity;
    for (let i = 0; i < count; ++i) {
      const x = v[i]!;
      if (Number.isFinite(x)) (lo = Math.min(lo, x), (hi = Math.max(hi, x)));
    }
    const span = hi > lo ? hi - lo : 1;
    for (let i = 0; i < count; ++i) {
      const x = v[i]!;
      if (Number.isFinite(x)) put(i, ...ramp((x - lo) / span));
      else put(i, 0, 0, 0);
    }
  } else if (modality === "normal") {
    for (let i = 0; i < count; ++i) {
      const c = (k: number) => Math.round(Math.min(Math.max(v[i * channels + k]! * 0.5 + 0.5, 0), 1) * 255);
      put(i, c(0), c(1), c(2));
    }
  } else if (modality === "position") {
    // Positions: the fraction of each coordinate in metres, a grid that shows the surfaces' shape.
    for (let i = 0; i < count; ++i) {
      const c = (k: number) => Math.round((((v[i * channels + k]! % 1) + 1) % 1) * 255);
      put(i, c(0), c(1), c(2));
    }
  } else {
    // Linear colours (HDR, base colour, illumination): clamped to [0, 1] and encoded with gamma 1/2.2.
    for (let i = 0; i < count; ++i) {
      const c = (k: number) => Math.round(Math.min(Math.max(v[i * channels + Math.min(k, channels - 1)]!, 0), 1) ** (1 / 2.2) * 255);
      put(i, c(0), c(1), c(2));
    }
  }
  return image;
}
