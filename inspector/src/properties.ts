// The property panel, built from the reflection data (REFLECTION in the generated API): one editor per value
// kind (numbers, text, booleans, enums as drop-downs, structs field by field with a colour picker for colours,
// object references as links), read-only where the property is. Edits go through the same "set" request as
// Python's, so the engine's setter runs and a refused value shows the engine's own error text.

import { getReflection, propertiesOf, SpearError, type PropertyDesc, type TypeDesc } from "./spear/client.js";
import { SpObject } from "../../generated/engine/ts/api.gen.js";

interface Editor {
  readonly element: HTMLElement;
  /** Shows the engine's value (unless the user is editing it). */
  update(value: unknown, force?: boolean): void;
}

type Commit = (value: unknown) => void;

function input(type: string, value: string, readOnly: boolean): HTMLInputElement {
  const element = document.createElement("input");
  element.type = type;
  element.value = value;
  element.disabled = readOnly;
  if (type === "number") element.step = "any";
  return element;
}

function editing(element: Element): boolean {
  return element.contains(document.activeElement);
}

interface Range {
  readonly min?: number | undefined;
  readonly max?: number | undefined;
}

function numberEditor(value: unknown, readOnly: boolean, integer: boolean, commit: Commit, range: Range = {}): Editor {
  const element = input("number", String(value), readOnly);
  if (integer) element.step = "1";
  if (range.min !== undefined) element.min = String(range.min);
  if (range.max !== undefined) element.max = String(range.max);
  element.addEventListener("change", () => {
    if (element.value.trim() === "" || !Number.isFinite(Number(element.value))) return; // still being typed
    commit(integer ? Math.trunc(Number(element.value)) : Number(element.value));
  });
  if (range.min === undefined && range.max === undefined) {
    return { element, update: (v, force) => (!force && editing(element)) || (element.value = String(v)) };
  }
  // A bounded number: its range beside it, and a slider where the range is one a hand can sweep.
  const box = document.createElement("span");
  box.className = "range";
  box.title = `in [${range.min ?? "-inf"}, ${range.max ?? "inf"}]`;
  box.append(element);
  let slider: HTMLInputElement | null = null;
  if (range.min !== undefined && range.max !== undefined && (!integer || range.max - range.min <= 100)) {
    slider = input("range", String(value), readOnly);
    slider.min = String(range.min);
    slider.max = String(range.max);
    slider.step = integer ? "1" : String((range.max - range.min) / 200);
    slider.addEventListener("input", () => (element.value = slider!.value));
    slider.addEventListener("change", () => commit(Number(slider!.value)));
    box.append(slider);
  } else {
    const label = document.createElement("span");
    label.className = "muted";
    label.textContent = box.title;
    box.append(label);
  }
  return {
    element: box,
    update: (v, force) => {
      if (!force && editing(box)) return;
      element.value = String(v);
      if (slider !== null) slider.value = String(v);
    },
  };
}

function linearToHex(r: number, g: number, b: number): string {
  const encode = (c: number) => {
    const s = c <= 0.0031308 ? 12.92 * c : 1.055 * Math.max(c, 0) ** (1 / 2.4) - 0.055;
    return Math.round(Math.min(Math.max(s, 0), 1) * 255).toString(16).padStart(2, "0");
  };
  return `#${encode(r)}${encode(g)}${encode(b)}`;
}

function hexToLinear(hex: string): [number, number, number] {
  const channel = (i: number) => {
    const s = parseInt(hex.slice(1 + 2 * i, 3 + 2 * i), 16) / 255;
    return s <= 0.04045 ? s / 12.92 : ((s + 0.055) / 1.055) ** 2.4;
  };
  return [channel(0), channel(1), channel(2)];
}

function structEditor(type: TypeDesc, value: unknown, readOnly: boolean, commit: Commit): Editor {
  const fields = getReflection().structs[type.name!]?.fields ?? [];
  const element = document.createElement("div");
  element.className = "editor";
  let current = { ...(value as Record<string, unknown>) };
  const editors = fields.map((field) => {
    const label = document.createElement("label");
    label.className = "field";
    label.textContent = field.name;
    const editor = valueEditor(field.type, current[field.name], readOnly, (v) => {
      current = { ...current, [field.name]: v };
      commit(current);
    }, () => undefined);
    label.append(editor.element);
    element.append(label);
    return { field, editor };
  });
  let swatch: HTMLInputElement | null = null;
  if (type.name === "FLinearColor") {
    const c = current as { R: number; G: number; B: number };
    swatch = input("color", linearToHex(c.R, c.G, c.B), readOnly);
    swatch.addEventListener("change", () => {
      const [R, G, B] = hexToLinear(swatch!.value);
      current = { ...current, R, G, B };
      commit(current);
    });
    element.prepend(swatch);
  }
  return {
    element,
    update: (v, force) => {
      if (!force && editing(element)) return;
      current = { ...(v as Record<string, unknown>) };
      for (const { field, editor } of editors) editor.update(current[field.name], force);
      const c = current as { R: number; G: number; B: number };
      if (swatch !== null) swatch.value = linearToHex(c.R, c.G, c.B);
    },
  };
}

function describe(value: unknown): string {
  if (value instanceof SpObject) return `${value.className} ${value.key}`;
  if (value !== null && typeof value === "object" && "dtype" in value && "shape" in value) {
    const array = value as { dtype: string; shape: number[] };
    return `${array.dtype}[${array.shape.join(", ")}]`;
  }
  return JSON.stringify(value, (_, v: unknown) => (v instanceof SpObject ? `${v.className} ${v.key}` : v));
}

/** How an object is named in the panel: its name from the outliner, else its class and handle. */
export type NameOf = (object: SpObject) => string;
let nameOf: NameOf = (object) => `${object.className} ${object.key}`;

/** An editor for a value of `type`; `select` is how an object reference's link selects its object. */
function valueEditor(type: TypeDesc, value: unknown, readOnly: boolean, commit: Commit,
                     select: (object: SpObject) => void, range: Range = {}): Editor {
  switch (type.kind) {
    case "bool": {
      const element = input("checkbox", "", readOnly);
      element.checked = value === true;
      element.addEventListener("change", () => commit(element.checked));
      return { element, update: (v, force) => (!force && editing(element)) || (element.checked = v === true) };
    }
    case "int":
    case "float":
      return numberEditor(value, readOnly, type.kind === "int", commit, range);
    case "str": {
      const element = input("text", String(value ?? ""), readOnly);
      element.addEventListener("change", () => commit(element.value));
      return { element, update: (v, force) => (!force && editing(element)) || (element.value = String(v ?? "")) };
    }
    case "enum": {
      const element = document.createElement("select");
      element.disabled = readOnly;
      for (const entry of getReflection().enums[type.name!]?.entries ?? []) {
        const option = document.createElement("option");
        option.value = String(entry.value);
        option.textContent = entry.name;
        element.append(option);
      }
      element.value = String(value);
      element.addEventListener("change", () => commit(Number(element.value)));
      return { element, update: (v, force) => (!force && editing(element)) || (element.value = String(v)) };
    }
    case "struct":
      return structEditor(type, value, readOnly, commit);
    case "object": {
      const element = document.createElement("span");
      const update = (v: unknown) => {
        element.replaceChildren();
        if (v instanceof SpObject) {
          const link = document.createElement("a");
          link.className = "object-link";
          link.textContent = nameOf(v);
          link.title = `${v.className} ${v.key}`;
          link.addEventListener("click", () => select(v));
          element.append(link);
        } else element.textContent = "None";
      };
      update(value);
      return { element, update };
    }
    case "list":
      if (["enum", "str", "int", "float", "bool"].includes(type.args![0]!.kind))
        return listEditor(type.args![0]!, value as unknown[], readOnly, commit, select);
      return shownOnly(value);
    default:
      return shownOnly(value);
  }
}

/** A value shown, not edited (dicts, classes, arrays, lists of structs or objects). */
function shownOnly(value: unknown): Editor {
  const element = document.createElement("span");
  element.className = "value";
  element.textContent = describe(value);
  return { element, update: (v) => (element.textContent = describe(v)) };
}

/** A list of plain values (names, numbers, enums): an editor per item, a button to remove it, one to add one. */
function listEditor(item: TypeDesc, value: unknown[], readOnly: boolean, commit: Commit,
                    select: (object: SpObject) => void): Editor {
  const element = document.createElement("div");
  element.className = "list";
  let items = [...(value ?? [])];
  const fresh = (): unknown =>
    item.kind === "enum" ? (getReflection().enums[item.name!]?.entries[0]?.value ?? 0)
      : item.kind === "str" ? "" : item.kind === "bool" ? false : 0;
  const render = () => {
    element.replaceChildren();
    items.forEach((current, i) => {
      const row = document.createElement("div");
      row.className = "item";
      const editor = valueEditor(item, current, readOnly, (v) => commit((items = items.map((x, j) => (j === i ? v : x)))),
                                 select);
      row.append(editor.element);
      if (!readOnly) {
        const remove = document.createElement("button");
        remove.textContent = "×";
        remove.title = "remove";
        remove.addEventListener("click", () => commit((items = items.filter((_, j) => j !== i))));
        row.append(remove);
      }
      element.append(row);
    });
    if (!readOnly) {
      const add = document.createElement("button");
      add.textContent = "+";
      add.title = "add an item";
      add.addEventListener("click", () => commit((items = [...items, fresh()])));
      element.append(add);
    }
  };
  render();
  return {
    element,
    update: (v, force) => {
      if (!force && editing(element)) return;
      items = [...((v as unknown[]) ?? [])];
      render();
    },
  };
}

export class PropertyPanel {
  private object: SpObject | null = null;
  private editors = new Map<string, Editor>();

  constructor(
    private readonly list: HTMLElement,
    private readonly select: (object: SpObject) => void,
    names: NameOf,
  ) {
    nameOf = names;
  }

  get selected(): SpObject | null {
    return this.object;
  }

  /** Builds the panel for `object`'s class and reads every property (one round trip). */
  async show(object: SpObject): Promise<void> {
    this.object = object;
    this.editors.clear();
    const properties = propertiesOf(object.className);
    const values = await Promise.all(properties.map((p) => object.get(p.name).catch((e: Error) => e)));
    if (this.object !== object) return; // another selection came first
    this.list.replaceChildren();
    let owner = "";
    properties.forEach((property, i) => {
      const declaredBy = this.declaringClass(object.className, property);
      if (declaredBy !== owner) {
        owner = declaredBy;
        const group = document.createElement("div");
        group.className = "group";
        group.textContent = owner;
        this.list.append(group);
      }
      this.list.append(this.row(object, property, values[i]));
    });
  }

  /** Re-reads the shown values (after frames ran), leaving alone the editor the user is in. */
  async refresh(): Promise<void> {
    const object = this.object;
    if (object === null) return;
    const names = [...this.editors.keys()];
    const values = await Promise.all(names.map((name) => object.get(name).catch(() => undefined)));
    if (this.object !== object) return;
    names.forEach((name, i) => values[i] !== undefined && this.editors.get(name)?.update(values[i]));
  }

  private declaringClass(className: string, property: PropertyDesc): string {
    const classes = getReflection().classes;
    for (let name: string | null = className; name !== null && classes[name] !== undefined; name = classes[name]!.parent)
      if (classes[name]!.properties.includes(property)) return name;
    return className;
  }

  private row(object: SpObject, property: PropertyDesc, value: unknown): HTMLElement {
    const row = document.createElement("div");
    row.className = "property";
    row.dataset["property"] = property.name;
    const name = document.createElement("div");
    name.className = "name";
    name.textContent = property.name;
    name.title = property.doc;
    const cell = document.createElement("div");
    cell.className = "editor";
    const error = document.createElement("div");
    error.className = "property-error";
    error.hidden = true;
    if (value instanceof Error) {
      cell.textContent = "(unreadable)";
      error.textContent = value.message;
      error.hidden = false;
      row.append(name, cell, error);
      return row;
    }
    const commit = (newValue: unknown) => {
      error.hidden = true;
      object
        .set(property.name, newValue)
        .catch((e: unknown) => {
          error.textContent = e instanceof SpearError ? `${e.type}: ${e.message}` : String(e);
          error.hidden = false;
        })
        .finally(() => object.get(property.name).then((v) => editor.update(v, true), () => undefined));
    };
    const editor = valueEditor(property.type, value, property.readOnly, commit, this.select, property);
    this.editors.set(property.name, editor);
    cell.append(editor.element);
    row.append(name, cell, error);
    return row;
  }
}
