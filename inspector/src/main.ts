// The inspector page: connects to spear-server with the token of its address (?token=), then keeps the outliner,
// the camera view and the property panel in step with the engine. It runs frames itself only when asked (Step,
// Run); while another client (a Python script) drives the frames it follows them, polling the frame count a few
// times a second. Its requests look at the world between frames without ticking it (client.ts: betweenFrames).

import { Outliner, readWorld } from "./outliner.js";
import { PropertyPanel } from "./properties.js";
import { SpearError } from "./spear/client.js";
import { Viewer, VIEWER_TAG } from "./viewer.js";
import { Viewport } from "./viewport.js";
import {
  ACameraSensorActor,
  API_HASH,
  Connection,
  UCameraSensorComponent,
  UWorld,
  type SpObject,
} from "../../generated/engine/ts/api.gen.js";

const $ = <T extends HTMLElement>(id: string) => document.getElementById(id) as T;
const POLL_MS = 250;
// While another client drives the frames, the view follows at most this often: each image costs the browser
// (on the machine the engine runs on, often) about 15 ms of CPU, which a frame loop on the same cores pays for.
const FOLLOW_MS = 500;

function log(text: string, error = false): void {
  const line = document.createElement("div");
  line.textContent = `${new Date().toLocaleTimeString()} ${text}`;
  if (error) line.className = "error";
  const box = $("log");
  box.prepend(line);
  while (box.childElementCount > 200) box.lastElementChild!.remove();
}

function status(text: string, error = false): void {
  const element = $("status");
  element.textContent = text;
  element.classList.toggle("error", error);
}

class Inspector {
  private world: UWorld | null = null; // the game world (the one a viewer camera goes into)
  private worlds: UWorld[] = [];
  private frame = -1;
  private lastDraw = 0;
  private existingViewer: ACameraSensorActor | null = null;
  private actorCount = "";
  private running = false;
  private busy = false;
  readonly outliner: Outliner;
  readonly panel: PropertyPanel;
  readonly viewport: Viewport;

  constructor(readonly connection: Connection) {
    const select = (object: SpObject) => void this.select(object);
    this.outliner = new Outliner($("outliner-tree"), $("outliner-search"), select);
    this.panel = new PropertyPanel($("property-list"), select, (object) => {
      const node = this.outliner.all().find((n) => n.object.equals(object));
      return node === undefined ? `${object.className} ${object.key}` : `${node.name} (${object.className})`;
    });
    this.viewport = new Viewport($("viewport-canvas"), $("camera-select"), $("modality-select"), $("viewport-info"),
                                 select);
    this.viewport.makeViewer = () => Viewer.of(this.world!, this.existingViewer, () => this.viewport.draw());
    $("step-button").addEventListener("click", () => void this.step());
    $("run-button").addEventListener("click", () => this.toggleRun());
  }

  async start(): Promise<void> {
    this.world = (await this.connection.send({ op: "world", kind: "game" })) as UWorld;
    await this.poll(true);
    document.body.dataset["ready"] = "true";
    setInterval(() => void this.poll(false), POLL_MS);
  }

  async select(object: SpObject): Promise<void> {
    this.outliner.select(object);
    $("selected-name").textContent = this.outliner.all().find((n) => n.object.equals(object))?.name ?? object.key;
    $("selected-class").textContent = object.className;
    document.body.dataset["selected"] = object.key;
    await this.panel.show(object);
  }

  /** Follows the engine: the frame count; the view and values when frames ran (at most every FOLLOW_MS while
   * another client drives them); the outliner when actors came or went. */
  private async poll(readScene: boolean): Promise<void> {
    if (this.busy || this.world === null) return;
    this.busy = true;
    try {
      const state = (await this.connection.send({ op: "frame", action: "state" })) as { state: string; frame_count: number };
      $("frame-owner").textContent = state.state === "idle" ? "" : `a frame is open (${state.state})`;
      if (readScene || (state.frame_count !== this.frame && performance.now() - this.lastDraw >= FOLLOW_MS))
        await this.show(state.frame_count, readScene);
      else $("frame-count").textContent = String(state.frame_count);
    } catch (error) {
      log(String(error), true);
    } finally {
      this.busy = false;
    }
  }

  /** Shows frame `frame`: its image and values, and the scene again when actors came or went (one round trip
   * when they did not: the calls of one turn travel together). */
  private async show(frame: number, readScene: boolean): Promise<void> {
    this.frame = frame;
    this.lastDraw = performance.now();
    $("frame-count").textContent = String(frame);
    const [count] = await Promise.all([this.countActors(), this.viewport.draw(), this.panel.refresh()]);
    if (readScene || count !== this.actorCount) {
      this.actorCount = count;
      await this.readScene();
      if (readScene) await this.viewport.draw(); // the cameras are known now
    }
  }

  /** Actors in every world, and worlds: a change in either means the outliner reads the scene again. The worlds
   * known so far are counted in the same message that lists them (a new world shows in the list, its count next
   * time), so following the engine costs one round trip. */
  private async countActors(): Promise<string> {
    const known = this.worlds.length > 0 ? this.worlds : [this.world!];
    const [worlds, ...counts] = await Promise.all([
      this.connection.call({ op: "worlds", action: "list" }) as Promise<UWorld[]>,
      ...known.map((w) => w.get_actor_count().catch(() => -1)), // (a world destroyed since)
    ]);
    this.worlds = worlds;
    return worlds.map((w) => w.key).join(" ") + " / " + counts.join(" ");
  }

  private async readScene(): Promise<void> {
    const worlds = await Promise.all((this.worlds.length > 0 ? this.worlds : [this.world!]).map(readWorld));
    this.outliner.show(worlds);
    const nodes = this.outliner.actors();
    // The scene's cameras to choose from; a viewer a page made before is the viewer again, not one of them.
    const viewer = nodes.find((actor) => actor.tags.includes(VIEWER_TAG) && actor.object instanceof ACameraSensorActor);
    this.existingViewer = (viewer?.object as ACameraSensorActor | undefined) ?? null;
    const cameras = nodes
      .filter((actor) => actor !== viewer)
      .flatMap((actor) =>
        actor.children
          .filter((c) => c.object instanceof UCameraSensorComponent)
          .map((c) => ({ camera: c.object as UCameraSensorComponent, label: `${actor.name}.${c.name}` })),
      );
    this.viewport.setCameras(cameras);
  }

  /** One frame: begin, tick, end, as one message; refused while another client's frame is open. */
  async step(): Promise<boolean> {
    const actions = ["begin", "execute", "begin_end", "end"] as const;
    const replies = await this.connection.batch(
      actions.map((action) => ({ op: "frame", action }) as const),
      { critical: [0, 1, 2, 3], betweenFrames: false },
    );
    const failed = replies.find((r) => r.error !== undefined);
    if (failed !== undefined) {
      log(`step: ${failed.error![0]}: ${failed.error![1]}`, true);
      return false;
    }
    // A frame the page ran itself is shown at once; the end's reply says which it was.
    await this.show((replies[3]!.ok as { frame_count: number }).frame_count, false);
    return true;
  }

  private toggleRun(): void {
    this.running = !this.running;
    $("run-button").textContent = this.running ? "Pause" : "Run";
    $("run-button").classList.toggle("active", this.running);
    if (this.running) void this.run();
  }

  private async run(): Promise<void> {
    while (this.running) {
      // Paced by the round trips: the engine is never asked for the next frame before this one was shown.
      if (!(await this.step())) await new Promise((resolve) => setTimeout(resolve, POLL_MS));
    }
  }
}

async function main(): Promise<void> {
  const token = new URLSearchParams(location.search).get("token") ?? "";
  let connection: Connection;
  try {
    connection = await Connection.open({ token, apiHash: API_HASH });
  } catch (error) {
    status(error instanceof SpearError ? `${error.type}: ${error.message}` : String(error), true);
    return;
  }
  connection.onClose = (reason) => status(reason, true);
  connection.onLog = (file, line, message) => log(`${file}:${line}: ${message}`);
  connection.onProgress = (task, done, total, finished) =>
    status(finished ? "connected" : `${task}: ${total > 0 ? Math.round((100 * done) / total) : done}%`);
  status("connected");
  const inspector = new Inspector(connection);
  (window as unknown as { spearInspector: Inspector }).spearInspector = inspector;
  await inspector.start();
}

void main();
