// The camera view: any camera sensor of the scene, any of its 14 modalities (one it does not render yet is added
// to its Modalities, an edit like any other, shown from the next frame on), drawn pixel for pixel on a canvas
// from the same read_pixels() a Python script gets. A click reads object_ids under the pointer and selects the
// actor that pixel shows (GetObjectIdInfo).

import { toRgba } from "./colors.js";
import { Viewer } from "./viewer.js";
import { ECameraModality, UCameraSensorComponent, type SpObject } from "../../generated/engine/ts/api.gen.js";

/** The modalities by their snake_case names (read_pixels' keys), in the enum's order. */
export const MODALITIES: readonly [string, ECameraModality][] = Object.entries(ECameraModality).map(
  ([name, value]) => [name.replace(/([a-z])([A-Z])/g, "$1_$2").toLowerCase(), value],
);

const VIEWER_OPTION = "viewer";

export class Viewport {
  private cameras: UCameraSensorComponent[] = [];
  private viewer: Viewer | null = null;
  /** Makes (or finds) the inspector's own camera, when the user first picks it (main.ts). */
  makeViewer: (() => Promise<Viewer>) | null = null;
  private idImage: Uint32Array | null = null;
  private idWidth = 0;
  /** The world frame the canvas shows (GetPixelsFrame), -1 before any. */
  shownFrame = -1;
  /** Images drawn so far (bench/bench_inspector.py counts the frames a viewer sees by it). */
  draws = 0;

  constructor(
    private readonly canvas: HTMLCanvasElement,
    private readonly cameraSelect: HTMLSelectElement,
    private readonly modalitySelect: HTMLSelectElement,
    private readonly info: HTMLElement,
    private readonly pick: (actor: SpObject) => void,
  ) {
    for (const [name] of MODALITIES) {
      const option = document.createElement("option");
      option.value = name;
      option.textContent = name;
      modalitySelect.append(option);
    }
    cameraSelect.addEventListener("change", () => void this.choose());
    modalitySelect.addEventListener("change", () => void this.draw());
    canvas.addEventListener("click", (event) => {
      if (canvas.dataset["dragged"] === "true") canvas.dataset["dragged"] = "false"; // the end of an orbit
      else void this.click(event);
    });
  }

  get viewerChosen(): boolean {
    return this.cameraSelect.value === VIEWER_OPTION;
  }

  get camera(): UCameraSensorComponent | null {
    if (this.viewerChosen) return this.viewer?.camera ?? null;
    return this.cameras[this.cameraSelect.selectedIndex] ?? null;
  }

  /** The camera picked: the viewer is made the first time, and rendered at once (a paused world shows too). */
  private async choose(): Promise<void> {
    if (this.viewerChosen && this.viewer === null && this.makeViewer !== null) {
      this.info.textContent = "making the viewer camera ...";
      this.viewer = await this.makeViewer();
      this.viewer.attach(this.canvas, () => this.viewerChosen);
      await this.viewer.move();
      return;
    }
    await this.draw();
  }

  get modality(): string {
    return this.modalitySelect.value;
  }

  /** The cameras to choose from, with their names (the selection is kept where it still exists). */
  setCameras(cameras: readonly { camera: UCameraSensorComponent; label: string }[]): void {
    const previous = this.camera;
    this.cameras = cameras.map((c) => c.camera);
    const wasViewer = this.viewerChosen;
    const viewer = document.createElement("option");
    viewer.value = VIEWER_OPTION;
    viewer.textContent = "viewer (drag, wheel, WASD QE)";
    this.cameraSelect.replaceChildren(
      ...cameras.map(({ camera, label }) => {
        const option = document.createElement("option");
        option.value = camera.key;
        option.textContent = label;
        return option;
      }),
      viewer,
    );
    const kept = previous === null ? -1 : this.cameras.findIndex((c) => c.equals(previous));
    this.cameraSelect.selectedIndex = wasViewer ? this.cameras.length : kept >= 0 ? kept : 0;
  }

  /** Reads the chosen camera's last frame and draws the chosen modality. */
  async draw(): Promise<void> {
    const camera = this.camera;
    if (camera === null) {
      this.info.textContent = "no camera in the scene: pick the viewer to look around";
      return;
    }
    const modality = this.modality;
    const wanted = MODALITIES.find(([name]) => name === modality)![1];
    const [pixels, frame, modalities] = await Promise.all([camera.read_pixels(), camera.GetPixelsFrame(),
                                                           camera.get("Modalities")]);
    if (!modalities.includes(wanted)) {
      // Rendered from the next frame on: the camera's own edit, visible in its properties.
      await camera.set("Modalities", [...modalities, wanted]);
      this.info.textContent = `${modality}: added to the camera's modalities; shown from the next frame`;
      return;
    }
    const array = (pixels as Record<string, unknown>)[modality] as Parameters<typeof toRgba>[1] | undefined;
    const ids = pixels.object_ids;
    this.idImage = ids ? (ids.data as Uint32Array) : null;
    this.idWidth = ids ? ids.shape[1]! : 0;
    if (array === undefined) {
      this.info.textContent = frame < 0 ? "the camera has not rendered a frame yet: step one" : `${modality}: none`;
      return;
    }
    const image = toRgba(modality, array);
    this.canvas.width = image.width;
    this.canvas.height = image.height;
    this.canvas.getContext("2d")!.putImageData(image, 0, 0);
    this.canvas.dataset["frame"] = String(frame);
    this.canvas.dataset["modality"] = modality;
    this.shownFrame = frame;
    this.draws += 1;
    this.info.textContent = `${image.width}×${image.height} ${array.dtype}, frame ${frame}` +
      (this.idImage === null ? " (add object_ids to pick by clicking)" : "");
  }

  private async click(event: MouseEvent): Promise<void> {
    const camera = this.camera;
    if (camera === null) return;
    const bounds = this.canvas.getBoundingClientRect();
    const x = Math.floor(((event.clientX - bounds.left) / bounds.width) * this.canvas.width);
    const y = Math.floor(((event.clientY - bounds.top) / bounds.height) * this.canvas.height);
    if (this.idImage === null) {
      // Picking reads object_ids: the camera renders them from the next frame on.
      const modalities = await camera.get("Modalities");
      if (!modalities.includes(ECameraModality.ObjectIds))
        await camera.set("Modalities", [...modalities, ECameraModality.ObjectIds]);
      this.info.textContent = "object_ids added to the camera's modalities: click again after a frame";
      return;
    }
    const id = this.idImage[y * this.idWidth + x] ?? 0;
    this.canvas.dataset["pickedId"] = String(id);
    const found = await camera.GetObjectIdInfo({ ObjectId: id });
    if (found.ReturnValue && found.Actor !== null) this.pick(found.Actor);
    else this.info.textContent = `pixel (${x}, ${y}): id ${id}, no object`;
  }
}
