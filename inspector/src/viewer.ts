// The inspector's own camera: an ACameraSensorActor named InspectorViewer (tagged "spear.inspector", so that a
// page opened later finds it again) that orbits a pivot point with the mouse and flies with the keys, and renders
// at once when it moves (UCameraSensorComponent.RenderNow), so that a paused world can be looked around too.
//
//   drag: orbit the pivot    wheel: nearer / farther    W A S D: move the pivot    Q E: down / up

import {
  ACameraSensorActor,
  ECameraModality,
  type FRotator,
  type FVector,
  type UCameraSensorComponent,
  type UWorld,
} from "../../generated/engine/ts/api.gen.js";

export const VIEWER_NAME = "InspectorViewer";
export const VIEWER_TAG = "spear.inspector";

const RAD = Math.PI / 180;

export class Viewer {
  // The pose as an orbit: the pivot, the direction looked in, and the distance from the pivot back to the camera.
  private pivot: FVector = { X: 0, Y: 0, Z: 0.8 };
  private yaw = 0;
  private pitch = -20;
  private distance = 6;
  private moving = false;
  private again = false;

  private constructor(
    readonly actor: ACameraSensorActor,
    readonly camera: UCameraSensorComponent,
    private readonly shown: () => Promise<void>,
  ) {}

  /** The viewer of `world`: the one a page made before (by its tag), else a new one at 640 x 480. */
  static async of(world: UWorld, existing: ACameraSensorActor | null, shown: () => Promise<void>): Promise<Viewer> {
    const actor =
      existing ??
      (await world.spawn_actor({
        uclass: ACameraSensorActor,
        name: VIEWER_NAME,
        tags: [VIEWER_TAG],
        location: { X: -6, Y: 0, Z: 3 },
      }));
    const camera = await actor.get("CameraSensor");
    if (existing === null) {
      await Promise.all([
        camera.set("Width", 640),
        camera.set("Height", 480),
        camera.set("Modalities", [ECameraModality.FinalColor, ECameraModality.ObjectIds]),
      ]);
    }
    const viewer = new Viewer(actor, camera, shown);
    const [location, rotation] = await Promise.all([actor.GetActorLocation(), actor.GetActorRotation()]);
    viewer.fromPose(location, rotation);
    return viewer;
  }

  /** Mouse and keys on `canvas` move this viewer while `active()` says it is the camera shown. */
  attach(canvas: HTMLCanvasElement, active: () => boolean): void {
    let dragging: { x: number; y: number; moved: boolean } | null = null;
    canvas.tabIndex = 0; // takes the keys once clicked
    canvas.addEventListener("mousedown", (event) => {
      if (active() && event.button === 0) dragging = { x: event.clientX, y: event.clientY, moved: false };
    });
    window.addEventListener("mouseup", () => (dragging = null));
    window.addEventListener("mousemove", (event) => {
      if (dragging === null || !active()) return;
      const dx = event.clientX - dragging.x;
      const dy = event.clientY - dragging.y;
      if (!dragging.moved && Math.hypot(dx, dy) < 3) return; // a click, not a drag
      dragging = { x: event.clientX, y: event.clientY, moved: true };
      canvas.dataset["dragged"] = "true";
      this.yaw += dx * 0.3;
      this.pitch = Math.min(Math.max(this.pitch - dy * 0.3, -89), 89);
      this.move();
    });
    canvas.addEventListener("wheel", (event) => {
      if (!active()) return;
      event.preventDefault();
      this.distance = Math.min(Math.max(this.distance * 1.1 ** (event.deltaY / 100), 0.2), 500);
      this.move();
    });
    canvas.addEventListener("keydown", (event) => {
      if (!active()) return;
      const step = 0.1 * this.distance;
      const forward = { X: Math.cos(this.yaw * RAD), Y: Math.sin(this.yaw * RAD) };
      const keys: Record<string, [number, number, number]> = {
        w: [forward.X, forward.Y, 0], s: [-forward.X, -forward.Y, 0], d: [-forward.Y, forward.X, 0],
        a: [forward.Y, -forward.X, 0], e: [0, 0, 1], q: [0, 0, -1],
      };
      const direction = keys[event.key.toLowerCase()];
      if (direction === undefined) return;
      this.pivot = { X: this.pivot.X + step * direction[0], Y: this.pivot.Y + step * direction[1],
                     Z: this.pivot.Z + step * direction[2] };
      this.move();
    });
  }

  /** The unit vector the camera looks along (X forward, Z up, as the engine's rotators). */
  private forward(): FVector {
    const p = this.pitch * RAD;
    const y = this.yaw * RAD;
    return { X: Math.cos(p) * Math.cos(y), Y: Math.cos(p) * Math.sin(y), Z: Math.sin(p) };
  }

  /** The camera's location and rotation for the orbit. */
  pose(): { location: FVector; rotation: FRotator } {
    const forward = this.forward();
    return {
      location: { X: this.pivot.X - forward.X * this.distance, Y: this.pivot.Y - forward.Y * this.distance,
                  Z: this.pivot.Z - forward.Z * this.distance },
      rotation: { Pitch: this.pitch, Yaw: this.yaw, Roll: 0 },
    };
  }

  private fromPose(location: FVector, rotation: FRotator): void {
    this.yaw = rotation.Yaw;
    this.pitch = Math.min(Math.max(rotation.Pitch, -89), 89);
    const forward = this.forward();
    this.pivot = { X: location.X + forward.X * this.distance, Y: location.Y + forward.Y * this.distance,
                   Z: location.Z + forward.Z * this.distance };
  }

  /** Moves the camera and renders it now; moves that come while one is on the way are merged into the next. */
  async move(): Promise<void> {
    if (this.moving) {
      this.again = true;
      return;
    }
    this.moving = true;
    try {
      do {
        this.again = false;
        const { location, rotation } = this.pose();
        await this.actor.K2_SetActorLocationAndRotation({ NewLocation: location, NewRotation: rotation });
        await this.camera.RenderNow();
        await this.shown();
      } while (this.again);
    } finally {
      this.moving = false;
    }
  }
}
