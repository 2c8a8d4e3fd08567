// A request is one of the protocol's messages (core/rpc/protocol.json, as the server spells them): a wrong
// literal, a misspelt field or an unknown op is refused where it is written.
import type { Connection } from "../../../../inspector/src/spear/client.js";

export async function misuse(connection: Connection): Promise<unknown[]> {
  return [
    await connection.send({ op: "frame", action: "begn" }),  // T: TS2820: Type '"begn"' is not assignable to type '"begin" | "execute" | "begin_end" | "end" | "abort" | "state"'. Did you mean '"begin"'?
    await connection.send({ op: "get", object: null, propery: "Tags" }),  // T: TS2561: Object literal may only specify known properties, but 'propery' does not exist in type 'GetMessage'. Did you mean to write 'property'?
    await connection.send({ op: "spawn", uclass: "AActor" }),  // T: TS2322: Type '"spawn"' is not assignable to type '"hello" | "shm_proof" | "world" | "worlds" | "frame" | "inspect" | "call" | "call_typed" | "get" | "get_typed" | "set" | "load_plugin" | "unload_plugin" | "sp_func" | "sp_func_names" | ... 4 more ... | "batch"'.
  ];
}
