// Compares builds of the package on a few representative calls, for the
// size/speed table of docs/performance.md:
//   node bench/node/compare.mjs <pkg dir> [<pkg dir> …]
// Each build runs in its own process, alternating, several rounds; per call
// it prints the median over rounds of each round's fastest time (the machine
// is shared, so the fastest of a round is the least disturbed).
import { execFileSync } from 'node:child_process';
import { fileURLToPath } from 'node:url';

const dirs = process.argv.slice(2);
const rounds = Number(process.env.ROUNDS || 5);
const worker = fileURLToPath(new URL('compare-one.mjs', import.meta.url));
const results = dirs.map(() => ({}));
for (let r = 0; r < rounds; r++) {
  dirs.forEach((d, k) => {
    const out = JSON.parse(execFileSync(process.execPath, [worker], { env: { ...process.env, MTMOTION_PKG: d }, encoding: 'utf8' }));
    for (const [name, ms] of Object.entries(out)) (results[k][name] ??= []).push(ms);
  });
}
const med = (a) => [...a].sort((x, y) => x - y)[Math.floor(a.length / 2)];
const names = Object.keys(results[0]);
console.log(['call', ...dirs].join(' | '));
for (const n of names) console.log([n, ...results.map((r) => med(r[n]).toFixed(3) + ' ms')].join(' | '));
