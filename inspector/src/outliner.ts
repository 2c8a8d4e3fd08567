// The outliner: the engine's worlds (the game world, then those create_world made), their actors and the actors'
// components as a tree, filtered by a search over names, classes and tags. It reads the scene through the generated API (find_actors, K2_GetComponents, GetName, Tags), all of one
// refresh in one round trip (the client batches calls made together).

import { AActor, UActorComponent, UWorld, type SpObject } from "../../generated/engine/ts/api.gen.js";

export interface OutlinerNode {
  readonly object: SpObject;
  readonly name: string;
  readonly className: string;
  readonly tags: readonly string[];
  readonly children: readonly OutlinerNode[];
}

async function componentNode(component: UActorComponent): Promise<OutlinerNode> {
  const [name, tags] = await Promise.all([component.GetName(), component.get("ComponentTags")]);
  return { object: component, name, className: component.className, tags, children: [] };
}

async function actorNode(actor: AActor): Promise<OutlinerNode> {
  const [name, tags, components] = await Promise.all([actor.GetName(), actor.get("Tags"), actor.K2_GetComponents()]);
  const children = await Promise.all(components.map(componentNode));
  return { object: actor, name, className: actor.className, tags, children };
}

/** A world with every actor of it and their components, in the world's order. */
export async function readWorld(world: UWorld): Promise<OutlinerNode> {
  const [name, actors] = await Promise.all([world.GetName(), world.find_actors()]);
  return { object: world, name, className: world.className, tags: [], children: await Promise.all(actors.map(actorNode)) };
}

function matches(node: OutlinerNode, query: string): boolean {
  const q = query.toLowerCase();
  return node.name.toLowerCase().includes(q) || node.className.toLowerCase().includes(q) ||
    node.tags.some((tag) => tag.toLowerCase().includes(q));
}

export class Outliner {
  private nodes: readonly OutlinerNode[] = [];
  private selected: SpObject | null = null;

  constructor(
    private readonly tree: HTMLElement,
    private readonly search: HTMLInputElement,
    private readonly onSelect: (object: SpObject) => void,
  ) {
    search.addEventListener("input", () => this.render());
  }

  /** Every node, worlds, actors and components, depth first. */
  all(): OutlinerNode[] {
    const walk = (node: OutlinerNode): OutlinerNode[] => [node, ...node.children.flatMap(walk)];
    return this.nodes.flatMap(walk);
  }

  /** The actors of every world, with their components. */
  actors(): OutlinerNode[] {
    return this.nodes.flatMap((world) => world.children);
  }

  show(nodes: readonly OutlinerNode[]): void {
    this.nodes = nodes;
    this.render();
  }

  select(object: SpObject | null): void {
    this.selected = object;
    for (const element of this.tree.querySelectorAll<HTMLElement>(".item"))
      element.classList.toggle("selected", object !== null && element.dataset["key"] === object.key);
  }

  private render(): void {
    const query = this.search.value.trim();
    this.tree.replaceChildren();
    for (const world of this.nodes) {
      this.tree.append(this.item(world, "world"));
      for (const actor of world.children) {
        // An actor that matches shows all its components; one that does not, those that match.
        const shown = query === "" || matches(actor, query);
        const children = shown ? actor.children : actor.children.filter((c) => matches(c, query));
        if (!shown && children.length === 0) continue;
        this.tree.append(this.item(actor, "actor"));
        if (children.length > 0) {
          const box = document.createElement("div");
          box.className = "children";
          box.append(...children.map((c) => this.item(c, "component")));
          this.tree.append(box);
        }
      }
    }
    this.select(this.selected);
  }

  private item(node: OutlinerNode, level: "world" | "actor" | "component"): HTMLElement {
    const element = document.createElement("div");
    element.className = `item ${level}`;
    element.dataset["key"] = node.object.key;
    element.dataset["name"] = node.name;
    element.dataset["class"] = node.className;
    element.title = node.tags.length > 0 ? `tags: ${node.tags.join(", ")}` : node.className;
    const name = document.createElement("span");
    name.textContent = node.name;
    const cls = document.createElement("span");
    cls.className = "class";
    cls.textContent = node.className;
    element.append(name, cls);
    element.addEventListener("click", () => this.onSelect(node.object));
    return element;
  }
}
