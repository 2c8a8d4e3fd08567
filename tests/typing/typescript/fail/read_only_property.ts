// set() takes only the properties that are not read-only, with their own types.
import type { ACameraSensorActor, UCameraSensorComponent } from "../../../../generated/engine/ts/api.gen.js";

export async function swap(actor: ACameraSensorActor, other: UCameraSensorComponent): Promise<void> {
  await actor.set("CameraSensor", other);  // T: TS2345: Argument of type '"CameraSensor"' is not assignable to parameter of type '"Tags"'.
  await other.set("Width", "wide");  // T: TS2345: Argument of type 'string' is not assignable to parameter of type 'number'.
}
