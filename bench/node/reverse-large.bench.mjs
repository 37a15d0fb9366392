// Reverse compensation of a generated 1 M-line CAM-like program in the
// wasm build (issue 27): the program of large-program.bench.mjs (0.2 mm
// G1 chords with a Z wave at F3000, 0.2 mm-radius G2/G3 half-circles
// between rows, four decimals), written to a temporary file by that
// script, then reverseCompensate with tA 40 ms, T 15 ms, dt 2 ms in a fresh
// Node process: the call's wall and CPU time, the wasm memory after it
// (memory.buffer.byteLength only grows: the peak) and the process's peak
// RSS, with the before/after maximum error and motion time. The `after`
// is the check's whole-program simulation of the written program against
// the original path (src/compensate/reverse, `check`), not a window's.
//   node bench/node/run.mjs reverse-large
//   LINES=200000 node bench/node/reverse-large.bench.mjs   (another size)
import { spawnSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir, loadavg } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = (f) => fileURLToPath(new URL(f, import.meta.url));
if (process.env.REVERSE_LARGE_CHILD === undefined) {
  const lines = Number(process.env.LINES ?? 1_000_000);
  const dir = mkdtempSync(join(tmpdir(), 'mtmotion-reverse-large-'));
  const file = join(dir, 'program.nc');
  const w = spawnSync(process.execPath, [here('large-program.bench.mjs'), '--write', file], { env: { ...process.env, LINES: String(lines) }, stdio: 'inherit' });
  if (w.status !== 0) throw new Error('could not write the generated program');
  const r = spawnSync(process.execPath, ['--max-old-space-size=4096', here('reverse-large.bench.mjs')], { env: { ...process.env, REVERSE_LARGE_CHILD: file, LINES: String(lines) }, stdio: 'inherit' });
  rmSync(dir, { recursive: true, force: true });
  if (r.status !== 0) process.exitCode = r.status ?? 1;
} else {
  const pkg = new URL('../../pkg/', import.meta.url);
  const wasm = await import(new URL('mtmotion.js', pkg).href);
  const exports = wasm.initSync({ module: readFileSync(new URL('mtmotion_bg.wasm', pkg)) });
  const text = readFileSync(process.env.REVERSE_LARGE_CHILD, 'latin1');
  const load = loadavg()[0];
  const cpu0 = process.cpuUsage();
  const t0 = performance.now();
  let line;
  try {
    const c = wasm.reverseCompensate(text, { tA: 0.04, T: 0.015, dt: 0.002 });
    line = `${c.before.maxErrorUm.toFixed(1)} -> ${c.after.maxErrorUm.toFixed(1)} µm (x${(c.after.maxErrorUm / c.before.maxErrorUm).toFixed(3)}), motion time ${c.before.motionTime.toFixed(1)} -> ${c.after.motionTime.toFixed(1)} s${c.budgetNote ? ', cut by the work budget' : ''}`;
  } catch (e) {
    line = `refused: ${String(e).slice(0, 300)}`;
  }
  const wall = (performance.now() - t0) / 1000;
  const cpu = process.cpuUsage(cpu0);
  console.log(`  ${process.env.LINES} lines: ${line}`);
  console.log(`  ${wall.toFixed(1)} s wall, ${((cpu.user + cpu.system) / 1e6).toFixed(1)} s CPU, load ${load.toFixed(1)}; wasm memory ${(exports.memory.buffer.byteLength / 2 ** 20).toFixed(0)} MiB, peak RSS ${(process.resourceUsage().maxRSS / 1024).toFixed(0)} MiB`);
}
