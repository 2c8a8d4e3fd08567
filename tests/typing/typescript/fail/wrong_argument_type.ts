// Arguments have their engine types: a string is no FVector, a missing required argument is named.
import type { AActor, UStaticMeshComponent } from "../../../../generated/engine/ts/api.gen.js";

export async function move(actor: AActor, mesh: UStaticMeshComponent): Promise<void> {
  await actor.SetActorLocation({ NewLocation: "over there" });  // T: TS2322: Type 'string' is not assignable to type 'FVector'.
  await mesh.SetStaticMesh({});  // T: TS2345: Argument of type '{}' is not assignable to parameter of type '{ NewMesh: string; }'.
}
