// Runs every Node benchmark of the wasm build: node bench/node/run.mjs [name…]
import { readdirSync } from 'node:fs';
const only = process.argv.slice(2);
const dir = new URL('.', import.meta.url);
for (const f of readdirSync(dir).filter((f) => f.endsWith('.bench.mjs')).sort()) {
  if (only.length && !only.some((o) => f.startsWith(o))) continue;
  console.log(`\n# ${f}`);
  await import(new URL(f, dir));
}
