#!/usr/bin/env node
// A SceneGraph collision filter in JavaScript, as a backend of the conformance harness.
//
// It speaks the worker protocol (docs/protocol.md): one JSON request per line on stdin,
// one JSON response per line on stdout. Run it with
//
//   python -m conformance run --backend exec:'node examples/node_backend/backend.js' --backend pydrake
//
// It implements the scenario features "core" and "transient" (the harness skips every case
// that needs another feature): a registry of sources, frames and geometries with roles,
// CollisionFilterDeclaration statements on geometry sets, Apply, ApplyTransient,
// RemoveDeclaration, IsActive, has_transient_history, CollisionFiltered and the candidate
// pairs. The filter follows Drake's geometry/proximity/collision_filter.cc: a composite
// state C, a persistent base, and a history of transient deltas replayed on the base.
// No npm dependencies.

"use strict";

const readline = require("readline");

const PROTOCOL = 1;
const NAME = "node-filter";
// The Drake release whose behaviour it claims (it was measured against pydrake 1.51.1).
const DRAKE_VERSION = "1.51.1";
const FEATURES = ["core", "transient"];

const WORLD = "world";
const MODEL = "model";
const DEFAULT_SOURCE = "source";
const UNKNOWN = "@unknown"; // an id no SceneGraph issued
const FOREIGN = "@foreign"; // an id issued by another SceneGraph

// How a pair stands in one filter state (collision_filter.h's PairRelationship).
const UNFILTERED = 0;
const FILTERED = 1;
const INVARIANT = 2; // filtered for good: same frame, or both anchored
const UNDEFINED = 3; // a transient delta says nothing about the pair

const TRANSIENT_HISTORY_MESSAGE =
  "You cannot attempt to modify the persistent collision filter configuration when there " +
  "are active, transient filter declarations";

// A name the command uses that no earlier command made: the input's fault (answered "unknown").
class UnknownName extends Error {
  constructor(kind, name) {
    super(`unknown ${kind} name '${name}'`);
    this.kind = kind;
    this.name_ = name;
  }
}

// What Drake would raise: answered as a Result with an error (kind, normalised message).
class DrakeError extends Error {
  constructor(kind, message) {
    super(message);
    this.kind = kind;
  }
}

// ---------------------------------------------------------------- the filter
// One filter state: pair key "i,j" (i < j, geometry ids) -> relationship.
function pairKey(a, b) {
  return a < b ? `${a},${b}` : `${b},${a}`;
}

class CollisionFilter {
  constructor(nextId) {
    this.nextId = nextId;
    this.ids = []; // the geometries in the filter (those with a proximity role)
    this.state = new Map(); // C: the composite state
    // Entry 0 is the persistent base; its id is never handed out, so it cannot be removed.
    this.history = [{ id: nextId(), state: new Map() }];
  }

  hasTransientHistory() {
    return this.history.length > 1;
  }

  addGeometry(id) {
    for (const other of this.ids) {
      const key = pairKey(id, other);
      this.state.set(key, UNFILTERED);
      this.history[0].state.set(key, UNFILTERED);
      for (const delta of this.history.slice(1)) delta.state.set(key, UNDEFINED);
    }
    this.ids.push(id);
  }

  removeGeometry(id) {
    this.ids = this.ids.filter((other) => other !== id);
    for (const state of [this.state, ...this.history.map((delta) => delta.state)]) {
      for (const key of [...state.keys()]) {
        const [a, b] = key.split(",").map(Number);
        if (a === id || b === id) state.delete(key);
      }
    }
  }

  canCollide(a, b) {
    return a !== b && this.state.get(pairKey(a, b)) === UNFILTERED;
  }

  // Apply: the persistent base and C, kept in step; refused while there is transient history.
  apply(statements, resolve, invariant) {
    if (this.hasTransientHistory()) {
      throw new DrakeError("transient_history", TRANSIENT_HISTORY_MESSAGE);
    }
    applyStatements(statements, resolve, invariant, this.state);
    applyStatements(statements, resolve, invariant, this.history[0].state);
  }

  applyTransient(statements, resolve) {
    applyStatements(statements, resolve, false, this.state);
    const delta = new Map();
    for (const key of this.state.keys()) delta.set(key, UNDEFINED);
    applyStatements(statements, resolve, false, delta);
    const id = this.nextId();
    this.history.push({ id, state: delta });
    return id;
  }

  isActive(id) {
    return this.history.some((delta) => delta.id === id);
  }

  // Removes a transient declaration: C is the base with the remaining deltas replayed in order.
  removeDeclaration(id) {
    const index = this.history.findIndex((delta, i) => i > 0 && delta.id === id);
    if (index < 0) return false;
    this.history.splice(index, 1);
    this.state = new Map(this.history[0].state);
    for (const delta of this.history.slice(1)) {
      for (const [key, relation] of delta.state) {
        if (relation !== UNDEFINED && this.state.get(key) !== INVARIANT) {
          this.state.set(key, relation);
        }
      }
    }
    return true;
  }
}

// Each statement resolves its sets when it runs (so a statement can fail after earlier ones
// changed the state, as in Drake), then sets every pair drawn across them, a != b.
function applyStatements(statements, resolve, invariant, state) {
  for (const statement of statements) {
    const within = statement.op.endsWith("_within");
    const setA = resolve(within ? statement.set : statement.a);
    const setB = within ? setA : resolve(statement.b);
    const exclude = statement.op.startsWith("exclude");
    for (const a of setA) {
      for (const b of setB) {
        if (a === b) continue;
        const key = pairKey(a, b);
        if (state.get(key) === INVARIANT) continue;
        state.set(key, exclude ? (invariant ? INVARIANT : FILTERED) : UNFILTERED);
      }
    }
  }
}

// ---------------------------------------------------------------- the scene graph
class SceneGraph {
  constructor() {
    let counter = 1;
    this.nextId = () => counter++;
    this.worldId = this.nextId();
    this.sources = new Map(); // name -> id
    this.frames = new Map([[WORLD, { id: this.worldId, geometries: [] }]]); // name -> frame
    this.geometries = new Map(); // name -> geometry (kept after removal: a stale id)
    this.byId = new Map(); // geometry id -> geometry (registered and not removed)
    this.labels = new Map(); // declaration label -> filter id
    this.filter = new CollisionFilter(this.nextId);
    this.unknownIds = new Map(); // "@unknown"/"@foreign" -> an id this scene never issued
  }

  // ---- names
  source(args) {
    const name = args.source === undefined ? DEFAULT_SOURCE : args.source;
    if (!this.sources.has(name)) {
      if (name !== DEFAULT_SOURCE) throw new UnknownName("source", name);
      this.sources.set(name, this.nextId());
    }
    return this.sources.get(name);
  }

  context(args) {
    if (args.context !== undefined && args.context !== MODEL) {
      throw new UnknownName("context", args.context);
    }
  }

  stranger(kind, name) {
    const key = `${kind}:${name}`;
    if (!this.unknownIds.has(key)) this.unknownIds.set(key, -this.unknownIds.size - 1);
    return this.unknownIds.get(key);
  }

  frame(name) {
    if (name === UNKNOWN || name === FOREIGN) return { id: this.stranger("frame", name) };
    const frame = this.frames.get(name);
    if (frame === undefined) throw new UnknownName("frame", name);
    return frame;
  }

  geometry(name) {
    if (name === UNKNOWN || name === FOREIGN) return { id: this.stranger("geometry", name) };
    const geometry = this.geometries.get(name);
    if (geometry === undefined) throw new UnknownName("geometry", name);
    return geometry;
  }

  filterId(label) {
    if (label === UNKNOWN) return this.stranger("filter", label);
    if (!this.labels.has(label)) throw new UnknownName("declaration label", label);
    return this.labels.get(label);
  }

  // GeometryState::CollectIds with the proximity role: a frame's own geometries (the world
  // frame's are the anchored ones, of every source), and listed geometries that have it.
  // Names are looked up first, so an unknown name is an input error, not a Drake error.
  resolver() {
    return (set) => {
      const frames = (set.frames || []).map((name) => this.frame(name));
      const geometries = (set.geometries || []).map((name) => this.geometry(name));
      const ids = new Set();
      for (const frame of frames) {
        if (frame.geometries === undefined) {
          throw new DrakeError("unknown_frame", "Referenced frame # has not been registered.");
        }
        for (const g of frame.geometries) if (this.byId.get(g).proximity) ids.add(g);
      }
      for (const geometry of geometries) {
        if (!this.byId.has(geometry.id)) {
          throw new DrakeError(
            "unknown_geometry",
            "Geometry set includes a geometry id that doesn't belong to the SceneGraph: #",
          );
        }
        if (geometry.proximity) ids.add(geometry.id);
      }
      return [...ids];
    };
  }

  // ---- commands (one per op of the grammar's core and transient rows)
  register_source(args) {
    this.sources.set(args.name, this.nextId());
  }

  register_frame(args) {
    const source = this.source(args);
    const parent = args.parent === undefined ? this.frames.get(WORLD) : this.frame(args.parent);
    this.frames.set(args.name, { id: this.nextId(), source, parent: parent.id, geometries: [] });
  }

  register_geometry(args) {
    this.context(args);
    this.source(args);
    const frame = this.frame(args.frame === undefined ? WORLD : args.frame);
    const geometry = { id: this.nextId(), frame: frame.id, roles: new Set(), proximity: false };
    frame.geometries.push(geometry.id);
    this.geometries.set(args.name, geometry);
    this.byId.set(geometry.id, geometry);
    for (const role of args.roles || []) this.assignRole(geometry, role, frame);
  }

  // AssignRole(kNew): a proximity geometry joins the filter, unfiltered with every other,
  // then its pairs with the geometries of its own frame become invariant (an Apply: refused
  // while there is transient history, after the geometry joined, as Drake does).
  assignRole(geometry, role, frame) {
    geometry.roles.add(role);
    if (role !== "proximity") return;
    geometry.proximity = true;
    this.filter.addGeometry(geometry.id);
    const statement = { op: "exclude_between", a: { ids: [geometry.id] }, b: { frame } };
    const resolve = (set) =>
      set.ids || set.frame.geometries.filter((g) => this.byId.get(g).proximity);
    this.filter.apply([statement], resolve, true);
  }

  remove_geometry(args) {
    this.context(args);
    this.source(args);
    const geometry = this.geometry(args.geometry);
    if (!this.byId.has(geometry.id)) {
      throw new DrakeError("unknown_geometry", "Referenced geometry # has not been registered.");
    }
    for (const frame of this.frames.values()) {
      frame.geometries = frame.geometries.filter((g) => g !== geometry.id);
    }
    if (geometry.proximity) this.filter.removeGeometry(geometry.id);
    this.byId.delete(geometry.id);
  }

  apply(args) {
    this.context(args);
    this.filter.apply(args.declaration.statements || [], this.resolver(), false);
  }

  // The label names the FilterId; if the call fails it names one never issued.
  apply_transient(args) {
    this.context(args);
    this.labels.set(args.label, this.stranger("failed", args.label));
    const id = this.filter.applyTransient(args.declaration.statements || [], this.resolver());
    this.labels.set(args.label, id);
  }

  remove_declaration(args) {
    this.context(args);
    return this.filter.removeDeclaration(this.filterId(args.label));
  }

  is_active(args) {
    this.context(args);
    return this.filter.isActive(this.filterId(args.label));
  }

  has_transient_history(args) {
    this.context(args);
    return this.filter.hasTransientHistory();
  }

  // SceneGraphInspector.CollisionFiltered, with its errors (geometry_state.cc).
  collision_filtered(args) {
    this.context(args);
    const [a, b] = args.pair.map((name) => this.geometry(name));
    const base = "Can't report collision filter status between geometries # and #; ";
    const valid = [a, b].map((g) => this.byId.has(g.id));
    if (!valid[0] || !valid[1]) {
      const which = valid[0] || valid[1] ? "# is not a valid geometry" : "neither id is a valid geometry";
      throw new DrakeError("invalid_query", base + which);
    }
    if (!a.proximity || !b.proximity) {
      const which =
        a.proximity || b.proximity ? "# does not have a proximity role" : " neither id has a proximity role";
      throw new DrakeError("invalid_query", base + which);
    }
    return !this.filter.canCollide(a.id, b.id);
  }

  // ---- the observation
  observe() {
    const names = new Map();
    for (const [name, geometry] of this.geometries) {
      if (this.byId.has(geometry.id)) names.set(geometry.id, name);
    }
    const candidates = [];
    const ids = this.filter.ids;
    for (let i = 0; i < ids.length; i++) {
      for (let j = i + 1; j < ids.length; j++) {
        if (this.filter.canCollide(ids[i], ids[j])) {
          candidates.push([names.get(ids[i]), names.get(ids[j])].sort());
        }
      }
    }
    candidates.sort((p, q) => (p[0] === q[0] ? compare(p[1], q[1]) : compare(p[0], q[0])));
    const active = {};
    for (const label of [...this.labels.keys()].sort()) {
      active[label] = this.filter.isActive(this.labels.get(label));
    }
    return {
      [MODEL]: {
        candidates,
        has_transient_history: this.filter.hasTransientHistory(),
        active,
      },
    };
  }
}

function compare(a, b) {
  return a < b ? -1 : a > b ? 1 : 0;
}

// ---------------------------------------------------------------- the protocol
const COMMANDS = new Set([
  "register_source",
  "register_frame",
  "register_geometry",
  "remove_geometry",
  "apply",
  "apply_transient",
  "remove_declaration",
  "is_active",
  "has_transient_history",
  "collision_filtered",
]);

let scene = new SceneGraph();

// A Result: the op's return value, or the Drake error it raised.
function execute(command) {
  const { op, ...args } = command;
  if (!COMMANDS.has(op)) throw new UnknownName("command", op);
  try {
    const value = scene[op](args);
    return { value: value === undefined ? null : value };
  } catch (error) {
    if (error instanceof DrakeError) return { error: { kind: error.kind, message: error.message } };
    throw error;
  }
}

const HANDLERS = {
  hello: () => ({ protocol: PROTOCOL, name: NAME, version: DRAKE_VERSION, features: FEATURES }),
  reset: () => {
    scene = new SceneGraph();
    return null;
  },
  arm_guards: () => null, // release guards protect Drake releases; this is not one
  execute: (request) => execute(request.command),
  observe: () => scene.observe(),
};

function raised(error) {
  const type = error instanceof UnknownName ? "UnknownNameError" : error.constructor.name;
  const answer = { raised: `${type}: ${error.message}`, type };
  if (error instanceof UnknownName) answer.unknown = [error.kind, error.name_];
  return answer;
}

function send(response) {
  process.stdout.write(JSON.stringify(response) + "\n");
}

function answer(request) {
  if (request.reset) scene = new SceneGraph();
  if (request.call === "steps") {
    // A batch: one line per step as it is done; a step that raises ends the batch.
    for (const step of request.steps) {
      try {
        const result = step.command === null ? { value: null } : execute(step.command);
        send({ value: { result, observation: step.observe ? scene.observe() : null } });
      } catch (error) {
        send(raised(error));
        return;
      }
    }
    return;
  }
  try {
    const handler = HANDLERS[request.call];
    if (handler === undefined) throw new Error(`unknown call '${request.call}'`);
    send({ value: handler(request) });
  } catch (error) {
    send(raised(error));
  }
}

readline.createInterface({ input: process.stdin }).on("line", (line) => answer(JSON.parse(line)));
