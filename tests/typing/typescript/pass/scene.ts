// A user's typed script against the generated client: spawning by class gives that class, properties and
// functions have their engine types, enums their names, camera modalities their arrays.
import {
  ACameraSensorActor,
  AStaticMeshActor,
  ECameraModality,
  type FVector,
  type NDArray,
  type UStaticMeshComponent,
  type UWorld,
} from "../../../../generated/engine/ts/api.gen.js";

export async function build(world: UWorld): Promise<number> {
  const crate = await world.spawn_actor({ uclass: AStaticMeshActor, name: "Crate", location: { X: 1, Y: 2, Z: 3 } });
  const mesh: UStaticMeshComponent = await crate.get("StaticMeshComponent"); // never null: NotNull
  await mesh.SetStaticMesh({ NewMesh: "/Engine/BasicShapes/Cube" });
  await mesh.set("RelativeLocation", { X: 0, Y: 0, Z: 1 });
  const where: FVector = await crate.GetActorLocation();
  const bounds = await crate.GetActorBounds({ bOnlyCollidingComponents: false }); // out-parameters by name
  const extent: FVector = bounds.BoxExtent;
  const tags: string[] = await crate.get("Tags");

  const camera = await world.spawn_actor({ uclass: ACameraSensorActor, name: "Cam" });
  const sensor = await camera.get("CameraSensor");
  await sensor.set("Modalities", [ECameraModality.FinalColor, ECameraModality.Depth]);
  await sensor.set("Width", 320);
  const pixels = await sensor.read_pixels();
  const depth: NDArray<"float32"> | undefined = pixels.depth;
  const actors = await world.find_actors();
  return where.X + extent.Z + tags.length + (depth?.shape[0] ?? 0) + actors.length;
}
