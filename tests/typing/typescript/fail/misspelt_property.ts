// A misspelt property name is refused where it is written, as mypy refuses it in Python.
import type { AActor } from "../../../../generated/engine/ts/api.gen.js";

export async function hide(actor: AActor): Promise<unknown> {
  return actor.get("RootComponnet");  // T: TS2345: Argument of type '"RootComponnet"' is not assignable to parameter of type 'keyof AActorProperties'.
}
