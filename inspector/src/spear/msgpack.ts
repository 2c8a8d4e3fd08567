// msgpack (https://github.com/msgpack/msgpack/blob/master/spec.md), the subset spear's protocol uses, with its
// extension types (core/rpc/value_msgpack.h): 1 object, 2 class, 3 array, 4 enum. Written here rather than
// taken from npm: the page then has no runtime dependency, and the extension types are decoded straight into
// the client's own types.

export const EXT_OBJECT = 1;
export const EXT_CLASS = 2;
export const EXT_ARRAY = 3;
export const EXT_ENUM = 4;

/** An extension value as it is on the wire; the encoder writes it as is. */
export class Ext {
  constructor(readonly type: number, readonly data: Uint8Array) {}
}

/** What decode() makes of an extension value; `tail` is the reply's tail (arrays sent after the message). */
export type ExtDecoder = (type: number, data: Uint8Array) => unknown;

export type Packable =
  | null
  | undefined
  | boolean
  | number
  | bigint
  | string
  | Uint8Array
  | Ext
  | readonly Packable[]
  | { readonly [key: string]: Packable };

const textEncoder = new TextEncoder();
const textDecoder = new TextDecoder();

class Writer {
  private bytes = new Uint8Array(256);
  private view = new DataView(this.bytes.buffer);
  length = 0;

  private reserve(n: number): void {
    if (this.length + n <= this.bytes.length) return;
    let size = this.bytes.length * 2;
    while (size < this.length + n) size *= 2;
    const grown = new Uint8Array(size);
    grown.set(this.bytes.subarray(0, this.length));
    this.bytes = grown;
    this.view = new DataView(grown.buffer);
  }
  u8(value: number): void {
    this.reserve(1);
    this.bytes[this.length++] = value;
  }
  u16(value: number): void {
    this.reserve(2);
    this.view.setUint16(this.length, value);
    this.length += 2;
  }
  u32(value: number): void {
    this.reserve(4);
    this.view.setUint32(this.length, value);
    this.length += 4;
  }
  f64(value: number): void {
    this.reserve(8);
    this.view.setFloat64(this.length, value);
    this.length += 8;
  }
  i64(value: bigint): void {
    this.reserve(8);
    this.view.setBigInt64(this.length, value);
    this.length += 8;
  }
  raw(data: Uint8Array): void {
    this.reserve(data.length);
    this.bytes.set(data, this.length);
    this.length += data.length;
  }
  result(): Uint8Array {
    return this.bytes.slice(0, this.length);
  }
}

function writeInteger(out: Writer, value: number): void {
  if (value >= 0) {
    if (value < 0x80) out.u8(value);
    else if (value < 0x100) (out.u8(0xcc), out.u8(value));
    else if (value < 0x10000) (out.u8(0xcd), out.u16(value));
    else if (value < 0x100000000) (out.u8(0xce), out.u32(value));
    else (out.u8(0xd3), out.i64(BigInt(value)));
  } else if (value >= -32) out.u8(value & 0xff);
  else if (value >= -0x80000000) {
    out.u8(0xd2);
    out.u32(value >>> 0);
  } else (out.u8(0xd3), out.i64(BigInt(value)));
}

function writeLength(out: Writer, size: number, fix: number, fixMax: number, codes: [number, number, number]): void {
  if (fix >= 0 && size <= fixMax) out.u8(fix | size);
  else if (codes[0] >= 0 && size < 0x100) (out.u8(codes[0]), out.u8(size));
  else if (size < 0x10000) (out.u8(codes[1]), out.u16(size));
  else (out.u8(codes[2]), out.u32(size));
}

function write(out: Writer, value: Packable, depth: number): void {
  if (depth > 64) throw new RangeError("msgpack: a value nested deeper than 64 levels");
  if (value === null || value === undefined) out.u8(0xc0);
  else if (value === false) out.u8(0xc2);
  else if (value === true) out.u8(0xc3);
  else if (typeof value === "number") {
    if (Number.isInteger(value) && Math.abs(value) <= Number.MAX_SAFE_INTEGER) writeInteger(out, value);
    else (out.u8(0xcb), out.f64(value));
  } else if (typeof value === "bigint") (out.u8(0xd3), out.i64(value));
  else if (typeof value === "string") {
    const bytes = textEncoder.encode(value);
    writeLength(out, bytes.length, 0xa0, 31, [0xd9, 0xda, 0xdb]);
    out.raw(bytes);
  } else if (value instanceof Uint8Array) {
    writeLength(out, value.length, -1, -1, [0xc4, 0xc5, 0xc6]);
    out.raw(value);
  } else if (value instanceof Ext) {
    const size = value.data.length;
    const fixed: Record<number, number> = { 1: 0xd4, 2: 0xd5, 4: 0xd6, 8: 0xd7, 16: 0xd8 };
    if (fixed[size] !== undefined) out.u8(fixed[size]);
    else writeLength(out, size, -1, -1, [0xc7, 0xc8, 0xc9]);
    out.u8(value.type);
    out.raw(value.data);
  } else if (Array.isArray(value)) {
    const items = value as readonly Packable[];
    writeLength(out, items.length, 0x90, 15, [-1, 0xdc, 0xdd]);
    for (const item of items) write(out, item, depth + 1);
  } else {
    const entries = Object.entries(value as { readonly [key: string]: Packable }).filter(([, v]) => v !== undefined);
    writeLength(out, entries.length, 0x80, 15, [-1, 0xde, 0xdf]);
    for (const [key, item] of entries) {
      write(out, key, depth + 1);
      write(out, item, depth + 1);
    }
  }
}

/** The msgpack encoding of `value`; keys whose value is undefined are left out (an argument left at its default). */
export function encode(value: Packable): Uint8Array {
  const out = new Writer();
  write(out, value, 0);
  return out.result();
}

/** Decodes one msgpack value from `bytes`; extension values go through `ext`. Throws RangeError when malformed. */
export function decode(bytes: Uint8Array, ext: ExtDecoder): unknown {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  let at = 0;
  const need = (n: number): void => {
    if (at + n > bytes.length) throw new RangeError("msgpack: a message cut short");
  };
  const str = (n: number): string => {
    need(n);
    const text = textDecoder.decode(bytes.subarray(at, at + n));
    at += n;
    return text;
  };
  const bin = (n: number): Uint8Array => {
    need(n);
    const data = bytes.subarray(at, at + n);
    at += n;
    return data;
  };
  const u8 = (): number => (need(1), bytes[at++]!);
  const u16 = (): number => (need(2), (at += 2), view.getUint16(at - 2));
  const u32 = (): number => (need(4), (at += 4), view.getUint32(at - 4));
  const int64 = (signed: boolean): number => {
    need(8);
    const value = signed ? view.getBigInt64(at) : view.getBigUint64(at);
    at += 8;
    // Numbers: the engine's integers (frame counts, ids) stay far below 2^53.
    return Number(value);
  };
  const array = (n: number, depth: number): unknown[] => {
    const items: unknown[] = [];
    for (let i = 0; i < n; ++i) items.push(read(depth + 1));
    return items;
  };
  const map = (n: number, depth: number): Record<string, unknown> => {
    const result: Record<string, unknown> = {};
    for (let i = 0; i < n; ++i) {
      const key = read(depth + 1);
      result[String(key)] = read(depth + 1);
    }
    return result;
  };
  const extension = (n: number): unknown => {
    const type = view.getInt8((need(1 + n), at));
    at += 1;
    return ext(type, bin(n));
  };
  function read(depth: number): unknown {
    if (depth > 128) throw new RangeError("msgpack: a value nested too deep");
    const code = u8();
    if (code < 0x80) return code;
    if (code < 0x90) return map(code & 0x0f, depth);
    if (code < 0xa0) return array(code & 0x0f, depth);
    if (code < 0xc0) return str(code & 0x1f);
    if (code >= 0xe0) return code - 0x100;
    switch (code) {
      case 0xc0: return null;
      case 0xc2: return false;
      case 0xc3: return true;
      case 0xc4: return bin(u8());
      case 0xc5: return bin(u16());
      case 0xc6: return bin(u32());
      case 0xc7: return extension(u8());
      case 0xc8: return extension(u16());
      case 0xc9: return extension(u32());
      case 0xca: return (need(4), (at += 4), view.getFloat32(at - 4));
      case 0xcb: return (need(8), (at += 8), view.getFloat64(at - 8));
      case 0xcc: return u8();
      case 0xcd: return u16();
      case 0xce: return u32();
      case 0xcf: return int64(false);
      case 0xd0: return (need(1), (at += 1), view.getInt8(at - 1));
      case 0xd1: return (need(2), (at += 2), view.getInt16(at - 2));
      case 0xd2: return (need(4), (at += 4), view.getInt32(at - 4));
      case 0xd3: return int64(true);
      case 0xd4: return extension(1);
      case 0xd5: return extension(2);
      case 0xd6: return extension(4);
      case 0xd7: return extension(8);
      case 0xd8: return extension(16);
      case 0xd9: return str(u8());
      case 0xda: return str(u16());
      case 0xdb: return str(u32());
      case 0xdc: return array(u16(), depth);
      case 0xdd: return array(u32(), depth);
      case 0xde: return map(u16(), depth);
      case 0xdf: return map(u32(), depth);
      default: throw new RangeError(`msgpack: unknown type byte 0x${code.toString(16)}`);
    }
  }
  return read(0);
}
