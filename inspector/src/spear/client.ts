// spear's RPC protocol over a WebSocket (spear-server --inspect): the runtime under the generated, typed API
// (generated/engine/ts/api.gen.ts), as spear/_rpc_client.py is under the generated Python proxies.
//
// A WebSocket message carries exactly the bytes of the socket transport (core/rpc/web.h): a length word, then
// a msgpack map; replies may carry large arrays raw after the message (the "tail", kTailFlag). Calls made in
// one turn of the event loop travel as one batch message, so a panel that reads thirty properties costs one
// round trip. With `betweenFrames`, calls may look at and edit the world while no frame is open, without
// ticking it (the dispatcher's between_frames batch).

import type { Message } from "../../../generated/rpc/ts/protocol.gen.js";
import { decode, encode, Ext, EXT_ARRAY, EXT_CLASS, EXT_ENUM, EXT_OBJECT, type Packable } from "./msgpack.js";

/** An error the engine (or the protocol) reported; `type` names the class, as spear.errors does in Python. */
export class SpearError extends Error {
  constructor(
    readonly type: string,
    message: string,
  ) {
    super(message);
    this.name = type;
  }
}

export type DType = "bool" | "uint8" | "int8" | "uint16" | "int16" | "uint32" | "int32" | "uint64" | "int64" |
  "float16" | "float32" | "float64";

/** An array as the engine sent it: its elements in `bytes` (little endian), `data` a typed view where one exists
 * (float16 has none in every browser yet: its raw 16-bit words are in `data` as a Uint16Array). */
export interface NDArray<D extends DType = DType> {
  readonly dtype: D;
  readonly shape: readonly number[];
  readonly bytes: Uint8Array;
  readonly data: ArrayBufferView;
}

const ELEMENT_SIZE: Record<DType, number> = {
  bool: 1, uint8: 1, int8: 1, uint16: 2, int16: 2, uint32: 4, int32: 4, uint64: 8, int64: 8, float16: 2,
  float32: 4, float64: 8,
};

function typedView(dtype: DType, bytes: Uint8Array): ArrayBufferView {
  // Typed arrays need aligned offsets: a misaligned slice (an inline array in a message) is copied first.
  const size = ELEMENT_SIZE[dtype];
  const aligned = bytes.byteOffset % size === 0 ? bytes : bytes.slice();
  const { buffer, byteOffset, byteLength } = aligned;
  const count = byteLength / size;
  switch (dtype) {
    case "float32": return new Float32Array(buffer, byteOffset, count);
    case "float64": return new Float64Array(buffer, byteOffset, count);
    case "uint32": return new Uint32Array(buffer, byteOffset, count);
    case "int32": return new Int32Array(buffer, byteOffset, count);
    case "uint16": case "float16": return new Uint16Array(buffer, byteOffset, count);
    case "int16": return new Int16Array(buffer, byteOffset, count);
    case "uint64": return new BigUint64Array(buffer, byteOffset, count);
    case "int64": return new BigInt64Array(buffer, byteOffset, count);
    case "int8": return new Int8Array(buffer, byteOffset, count);
    default: return aligned;
  }
}

/** An engine class passed by name (a TSubclassOf parameter or result). */
export class ClassRef {
  constructor(readonly name: string) {}
}

/** Marks an enum argument with its enum's name: the engine refuses a bare number where an enum is declared. */
export function enumArg(enumName: string, value: number): Ext {
  const data = new Uint8Array(8 + enumName.length);
  new DataView(data.buffer).setBigInt64(0, BigInt(value), true);
  data.set(new TextEncoder().encode(enumName), 8);
  return new Ext(EXT_ENUM, data);
}

/** A class argument: a generated class (AActor) or its name. */
export function classArg(value: { readonly spClass: string } | string): Ext {
  return new Ext(EXT_CLASS, new TextEncoder().encode(typeof value === "string" ? value : value.spClass));
}

/** The reflection data of the generated API (REFLECTION in api.gen.ts): the IR's classes, structs and enums. */
export interface TypeDesc {
  readonly kind: "void" | "bool" | "int" | "float" | "str" | "enum" | "struct" | "object" | "class" | "list" | "dict" |
    "array";
  readonly name?: string;
  readonly args?: readonly TypeDesc[];
}
export interface PropertyDesc {
  readonly name: string;
  readonly type: TypeDesc;
  readonly readOnly: boolean;
  readonly notNull: boolean;
  readonly doc: string;
  /** The range an editor offers (ClampMin / ClampMax); the engine's setter checks values all the same. */
  readonly min?: number;
  readonly max?: number;
}
export interface FunctionDesc {
  readonly static: boolean;
  readonly params: readonly { readonly name: string; readonly type: TypeDesc; readonly optional: boolean }[];
}
export interface ClassDesc {
  readonly parent: string | null;
  readonly doc: string;
  readonly abstract: boolean;
  readonly properties: readonly PropertyDesc[];
  readonly functions: { readonly [name: string]: FunctionDesc };
}
export interface Reflection {
  readonly apiHash: string;
  readonly classes: { readonly [name: string]: ClassDesc };
  readonly structs: { readonly [name: string]: { readonly doc: string; readonly fields: readonly { readonly name: string; readonly type: TypeDesc }[] } };
  readonly enums: { readonly [name: string]: { readonly doc: string; readonly entries: readonly { readonly name: string; readonly value: number }[] } };
}

let reflection: Reflection = { apiHash: "", classes: {}, structs: {}, enums: {} };

/** Installs the generated API's reflection data (api.gen.ts does, once). */
export function registerApi(data: Reflection): void {
  reflection = data;
}

export function getReflection(): Reflection {
  return reflection;
}

/** A generated class as an argument: the class itself (AStaticMeshActor), whose instances are T. */
export type SpClass<T extends SpObject> = { readonly spClass: string; prototype: T };

type ProxyConstructor = new (connection: Connection, index: number, generation: number, className: string) => SpObject;
const proxies = new Map<string, ProxyConstructor>();

/** Records the proxy class of an engine class (the generated API calls this for each of its classes). */
export function registerProxy(className: string, proxy: ProxyConstructor): void {
  proxies.set(className, proxy);
}

/** The class and its bases, nearest first, as far as the reflection data knows them. */
export function classChain(className: string): string[] {
  const chain: string[] = [];
  for (let name: string | null = className; name !== null && reflection.classes[name] !== undefined;
       name = reflection.classes[name]!.parent)
    chain.push(name);
  return chain;
}

/** Whether `className` is `base` or derives from it. */
export function isSubclass(className: string, base: string): boolean {
  return classChain(className).includes(base);
}

/** The properties of a class and its bases, the bases' first (as the inspector lists them). */
export function propertiesOf(className: string): PropertyDesc[] {
  return classChain(className).reverse().flatMap((name) => reflection.classes[name]!.properties);
}

function findFunction(className: string, fn: string): FunctionDesc | undefined {
  for (const name of classChain(className)) {
    const found = reflection.classes[name]!.functions[fn];
    if (found !== undefined) return found;
  }
  return undefined;
}

function findProperty(className: string, property: string): PropertyDesc | undefined {
  return propertiesOf(className).find((p) => p.name === property);
}

/** A value as the wire carries it for its declared type: enums and classes marked, objects as handles, arrays
 * as extension type 3. Values of the wrong shape go as they are: the engine refuses them with its own message. */
export function toWire(type: TypeDesc | undefined, value: unknown): Packable {
  if (type === undefined || value === null || value === undefined) return value as Packable;
  switch (type.kind) {
    case "enum":
      return typeof value === "number" ? enumArg(type.name!, value) : (value as Packable);
    case "object":
      return value instanceof SpObject ? value.ext : (value as Packable);
    case "class":
      return typeof value === "string" || (typeof value === "function" && "spClass" in value)
        ? classArg(value as { readonly spClass: string } | string)
        : (value as Packable);
    case "struct": {
      const fields = reflection.structs[type.name!]?.fields;
      if (fields === undefined || typeof value !== "object") return value as Packable;
      const out: Record<string, Packable> = {};
      for (const [key, item] of Object.entries(value as Record<string, unknown>))
        out[key] = toWire(fields.find((f) => f.name === key)?.type, item);
      return out;
    }
    case "list":
      return Array.isArray(value) ? value.map((item) => toWire(type.args![0], item)) : (value as Packable);
    case "dict": {
      if (typeof value !== "object") return value as Packable;
      const out: Record<string, Packable> = {};
      for (const [key, item] of Object.entries(value as Record<string, unknown>)) out[key] = toWire(type.args![0], item);
      return out;
    }
    case "array": {
      const array = value as NDArray;
      if (!(array.bytes instanceof Uint8Array)) return value as Packable;
      return new Ext(EXT_ARRAY, encode([array.dtype, [...array.shape], array.bytes]));
    }
    default:
      return value as Packable;
  }
}

function encodeArgs(fn: FunctionDesc | undefined, args: Record<string, unknown>): Record<string, Packable> {
  const out: Record<string, Packable> = {};
  for (const [name, value] of Object.entries(args)) {
    if (value === undefined) continue; // left at its default: the engine applies the C++ default
    out[name] = toWire(fn?.params.find((p) => p.name === name)?.type, value);
  }
  return out;
}

/** An engine object on the other side of the connection: its handle and its class. */
export class SpObject {
  constructor(
    readonly connection: Connection,
    readonly index: number,
    readonly generation: number,
    readonly className: string,
  ) {}

  /** The handle as the wire spells it (extension type 1). */
  get ext(): Ext {
    const data = new Uint8Array(8);
    const view = new DataView(data.buffer);
    view.setUint32(0, this.index, true);
    view.setUint32(4, this.generation, true);
    return new Ext(EXT_OBJECT, data);
  }

  /** A key that names the object for good (an index is reused only with a new generation). */
  get key(): string {
    return `${this.index}:${this.generation}`;
  }

  equals(other: SpObject | null | undefined): boolean {
    return other != null && other.index === this.index && other.generation === this.generation;
  }

  /** Calls a reflected function by name, its arguments encoded by their declared types. */
  protected spInvoke<T>(fn: string, args: Record<string, unknown> = {}): Promise<T> {
    const desc = findFunction(this.className, fn);
    return this.connection.call({ op: "call", object: this.ext, function: fn, args: encodeArgs(desc, args) }) as Promise<T>;
  }

  protected spGet<T>(property: string): Promise<T> {
    return this.connection.call({ op: "get", object: this.ext, property }) as Promise<T>;
  }

  protected spSet(property: string, value: unknown): Promise<void> {
    const type = findProperty(this.className, property)?.type;
    return this.connection.call({ op: "set", object: this.ext, property, value: toWire(type, value) }) as Promise<void>;
  }

  /** A property by name (the generated classes narrow this to their properties' names and types). */
  get(name: string): Promise<unknown> {
    return this.spGet<unknown>(name);
  }

  /** Sets a property by name through the engine's setter. */
  set(name: string, value: unknown): Promise<void> {
    return this.spSet(name, value);
  }

  /** Whether the object still exists. */
  isValid(): Promise<boolean> {
    return this.connection.call({ op: "is_valid", object: this.ext }) as Promise<boolean>;
  }
}

/** Calls a static function of a class. */
export function callStatic<T>(connection: Connection, className: string, fn: string,
                              args: Record<string, unknown> = {}): Promise<T> {
  const desc = reflection.classes[className]?.functions[fn];
  return connection.call({ op: "call", class: className, function: fn, args: encodeArgs(desc, args) }) as Promise<T>;
}

/** A request: one of the protocol's messages (generated from core/rpc/protocol.json). */
export type Request = Message;

interface Pending {
  resolve: (value: unknown) => void;
  reject: (error: Error) => void;
}

const TAIL_FLAG = 0x80000000;
const TAIL_ALIGNMENT = 64;

export interface ConnectOptions {
  /** ws://host:port/ (default: the page's own host). */
  url?: string;
  token: string;
  apiHash: string;
}

export class Connection {
  /** Whether calls may act while no frame is open, without ticking the world (see the file's notes). */
  betweenFrames = true;
  /** Called once when the connection is gone. */
  onClose: ((reason: string) => void) | null = null;
  /** The engine's log lines, as it writes them (file, line, message). */
  onLog: ((file: string, line: number, message: string) => void) | null = null;
  /** Progress of long work (a scene loading, a path-traced frame): the latest report of each task. */
  onProgress: ((task: string, done: number, total: number, finished: boolean) => void) | null = null;

  private nextId = 1;
  private readonly pending = new Map<number, Pending>();
  private queue: { request: Request; pending: Pending }[] = [];
  private flushScheduled = false;
  private closed = false;

  private constructor(private readonly socket: WebSocket) {
    socket.binaryType = "arraybuffer";
    socket.onmessage = (event: MessageEvent) => this.receive(new Uint8Array(event.data as ArrayBuffer));
    socket.onclose = () => this.fail("the connection to spear-server closed");
    socket.onerror = () => this.fail("the connection to spear-server failed");
  }

  /** Opens a WebSocket to the server and says hello with the token; rejects with the server's refusal. */
  static async open(options: ConnectOptions): Promise<Connection> {
    const url = options.url ?? `ws://${location.host}/`;
    const socket = new WebSocket(url);
    await new Promise<void>((resolve, reject) => {
      socket.onopen = () => resolve();
      socket.onerror = () => reject(new SpearError("ConnectionError", `cannot connect to ${url}`));
    });
    const connection = new Connection(socket);
    await connection.send({ op: "hello", api_hash: options.apiHash, token: options.token });
    return connection;
  }

  close(): void {
    this.socket.close();
  }

  /** One call, sent with the others made in this turn of the event loop as one batch. */
  call(request: Request): Promise<unknown> {
    return new Promise((resolve, reject) => {
      this.queue.push({ request, pending: { resolve, reject } });
      if (!this.flushScheduled) {
        this.flushScheduled = true;
        queueMicrotask(() => this.flush());
      }
    });
  }

  /** A request on its own (hello, frame operations, echo), not batched. */
  send(request: Request): Promise<unknown> {
    if (this.closed) return Promise.reject(new SpearError("ConnectionError", "the connection is closed"));
    const id = this.nextId++;
    const body = encode({ ...request, id });
    const frame = new Uint8Array(4 + body.length);
    new DataView(frame.buffer).setUint32(0, body.length, true);
    frame.set(body, 4);
    return new Promise((resolve, reject) => {
      this.pending.set(id, { resolve, reject });
      this.socket.send(frame);
    });
  }

  /** Several requests in one message, run in order; a failed critical one stops the rest (a frame's steps).
   * Resolves with each one's reply ({ok} or {error: [type, message]}). */
  batch(requests: readonly Request[], options: { critical?: readonly number[]; betweenFrames?: boolean } = {}):
    Promise<{ ok?: unknown; error?: [string, string] }[]> {
    return this.send({
      op: "batch",
      calls: requests,
      critical: options.critical ?? [],
      between_frames: options.betweenFrames ?? this.betweenFrames,
    }) as Promise<{ ok?: unknown; error?: [string, string] }[]>;
  }

  private flush(): void {
    this.flushScheduled = false;
    const queue = this.queue;
    this.queue = [];
    if (queue.length === 0) return;
    this.send({ op: "batch", calls: queue.map((q) => q.request), between_frames: this.betweenFrames }).then(
      (replies) => {
        (replies as unknown[]).forEach((reply, i) => {
          const { resolve, reject } = queue[i]!.pending;
          const fields = reply as { ok?: unknown; error?: [string, string] };
          if (fields.error !== undefined) reject(new SpearError(fields.error[0], fields.error[1]));
          else resolve(fields.ok);
        });
      },
      (error: Error) => queue.forEach((q) => q.pending.reject(error)),
    );
  }

  private receive(frame: Uint8Array): void {
    const view = new DataView(frame.buffer, frame.byteOffset, frame.byteLength);
    const word = view.getUint32(0, true);
    let message: Uint8Array;
    let tail: Uint8Array | null = null;
    if (word & TAIL_FLAG) {
      // [length | flag][message length][message][padding][tail], the tail aligned from the byte after the word.
      const size = view.getUint32(4, true);
      message = frame.subarray(8, 8 + size);
      const start = 4 + Math.ceil((4 + size) / TAIL_ALIGNMENT) * TAIL_ALIGNMENT;
      tail = frame.subarray(start);
    } else message = frame.subarray(4, 4 + word);
    let reply: { id?: number; ok?: unknown; error?: [string, string] };
    try {
      reply = decode(message, (type, data) => this.extension(type, data, tail)) as typeof reply;
    } catch (error) {
      this.fail(`a malformed reply from spear-server: ${String(error)}`);
      return;
    }
    if (reply.id === undefined) {
      // Not a reply: what the server sends browsers unasked (core/rpc/server.cpp, Broadcast).
      const push = reply as { log?: [string, number, string]; progress?: [string, number, number, boolean] };
      if (push.log !== undefined) this.onLog?.(...push.log);
      if (push.progress !== undefined) this.onProgress?.(...push.progress);
      return;
    }
    const pending = this.pending.get(reply.id);
    if (pending === undefined) return;
    this.pending.delete(reply.id!);
    if (reply.error !== undefined) pending.reject(new SpearError(reply.error[0], reply.error[1]));
    else pending.resolve(reply.ok);
  }

  private extension(type: number, data: Uint8Array, tail: Uint8Array | null): unknown {
    const view = new DataView(data.buffer, data.byteOffset, data.byteLength);
    if (type === EXT_OBJECT) {
      const index = view.getUint32(0, true);
      const generation = view.getUint32(4, true);
      const className = new TextDecoder().decode(data.subarray(8));
      const proxy = proxies.get(className) ?? nearestProxy(className);
      return new proxy(this, index, generation, className);
    }
    if (type === EXT_CLASS) return new ClassRef(new TextDecoder().decode(data).split("\0")[0]!);
    if (type === EXT_ARRAY) {
      const [dtype, shape, payload] = decode(data, () => null) as [DType, number[], unknown];
      let bytes: Uint8Array;
      if (payload instanceof Uint8Array) bytes = payload;
      else {
        const place = payload as { tail?: number; size: number };
        if (tail === null || place.tail === undefined || place.tail + place.size > tail.length)
          throw new RangeError("an array outside its reply");
        bytes = tail.subarray(place.tail, place.tail + place.size);
      }
      return { dtype, shape, bytes, data: typedView(dtype, bytes) } satisfies NDArray;
    }
    if (type === EXT_ENUM) return Number(view.getBigInt64(0, true));
    return new Ext(type, data);
  }

  private fail(reason: string): void {
    if (this.closed) return;
    this.closed = true;
    for (const pending of this.pending.values()) pending.reject(new SpearError("ConnectionError", reason));
    this.pending.clear();
    this.onClose?.(reason);
  }
}

function nearestProxy(className: string): ProxyConstructor {
  // A class the generated API does not know (a plugin's): the proxy of its nearest known base, else the bare one.
  for (const name of classChain(className)) {
    const proxy = proxies.get(name);
    if (proxy !== undefined) return proxy;
  }
  return proxies.get("UObject") ?? SpObject;
}
