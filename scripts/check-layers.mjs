#!/usr/bin/env node
// Fails (exit 1) when a module of the Rust core imports a module of its own
// layer or of a layer above it, or when the imports form a cycle. The layer
// table below is the one drawn in ARCHITECTURE.md; a new top-level module
// must be added to it (an unknown module fails the check).
//
// What counts as an import: every `crate::<module>` path (including the
// names inside `crate::{a, b::c}`) in code, outside comments and outside the
// unit-test module at the end of a file (everything after a line starting
// with `#[cfg(test)]`: tests may build fixtures from presets above them).
//
// Usage: node scripts/check-layers.mjs [src-dir]   (default: src)
import { readdirSync, readFileSync, statSync } from 'node:fs';
import { join, basename } from 'node:path';

export const LAYERS = [
  ['trace', 'budget', 'numeric', 'axes'],
  ['servo', 'nc', 'ballbar', 'kinematics'],
  ['toolpath', 'alignment'],
  ['machine'],
  ['feed_vector', 'cone_frustum', 'compensate'],
  ['best_kffp'],
  ['wasm'],
];
const rank = new Map(LAYERS.flatMap((mods, i) => mods.map((m) => [m, i])));

function rustFiles(path) {
  if (statSync(path).isFile()) return path.endsWith('.rs') ? [path] : [];
  return readdirSync(path).flatMap((f) => rustFiles(join(path, f)));
}

/** Top-level modules referenced from one file's non-test code. */
export function importsOf(text) {
  const out = new Set();
  for (const raw of text.split('\n')) {
    if (raw.startsWith('#[cfg(test)]')) break;
    const line = raw.replace(/\/\/.*$/, '');
    for (const m of line.matchAll(/crate::(\{[^}]*\}|\w+)/g)) {
      const target = m[1];
      if (target.startsWith('{')) {
        for (const part of target.slice(1, -1).split(',')) {
          const name = part.trim().split('::')[0];
          if (name) out.add(name);
        }
      } else out.add(target);
    }
  }
  return out;
}

/** `{ problems: string[], graph }` for the core under `src`. */
export function checkLayers(src) {
  const problems = [];
  const graph = new Map();
  for (const entry of readdirSync(src)) {
    if (entry === 'lib.rs' || entry === 'main.rs') continue;
    const mod = basename(entry, '.rs');
    if (!rank.has(mod)) {
      problems.push(`src/${entry}: module '${mod}' is not in the layer table of scripts/check-layers.mjs (and ARCHITECTURE.md); add it to the layer it belongs to`);
      continue;
    }
    const deps = graph.get(mod) ?? new Map();
    for (const file of rustFiles(join(src, entry))) {
      for (const dep of importsOf(readFileSync(file, 'utf8'))) {
        if (dep === mod || !/^[a-z_0-9]+$/.test(dep)) continue;
        if (!deps.has(dep)) deps.set(dep, file);
      }
    }
    graph.set(mod, deps);
  }
  for (const [mod, deps] of graph) {
    for (const [dep, file] of deps) {
      if (!rank.has(dep)) continue; // not a top-level module of ours (e.g. a macro path)
      const a = rank.get(mod);
      const b = rank.get(dep);
      if (b > a) problems.push(`${file}: '${mod}' (layer ${a}) imports '${dep}' from the layer above it (layer ${b}): an upward import`);
      else if (b === a) problems.push(`${file}: '${mod}' imports '${dep}' from its own layer (${a}): a sideways import; move the shared part down`);
    }
  }
  // Cycles, named explicitly (DFS over the module graph).
  const state = new Map();
  const stack = [];
  const visit = (m) => {
    state.set(m, 1);
    stack.push(m);
    for (const d of graph.get(m)?.keys() ?? []) {
      if (!graph.has(d)) continue;
      if (state.get(d) === 1) problems.push(`import cycle: ${[...stack.slice(stack.indexOf(d)), d].join(' -> ')}`);
      else if (!state.has(d)) visit(d);
    }
    stack.pop();
    state.set(m, 2);
  };
  for (const m of graph.keys()) if (!state.has(m)) visit(m);
  return { problems, graph };
}

if (import.meta.url === `file://${process.argv[1]}`) {
  const src = process.argv[2] ?? 'src';
  const { problems, graph } = checkLayers(src);
  if (problems.length) {
    console.error(`check-layers: ${problems.length} problem(s) in ${src}:`);
    for (const p of problems) console.error(`  ${p}`);
    process.exit(1);
  }
  console.log(`check-layers: ${graph.size} modules, ${[...graph.values()].reduce((n, d) => n + [...d.keys()].filter((k) => rank.has(k)).length, 0)} module imports, all downward, no cycle`);
}
