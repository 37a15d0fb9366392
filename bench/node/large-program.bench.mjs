// A generated CAM-like finishing program of 2,000,000 lines (59 MiB):
// short G1 chords with a Z wave, small G2/G3 arcs at the row ends, feed
// changes and comments, as a Fusion 360 or Mastercam finishing post
// writes. In a fresh Node process per size it is checked (checkNc) and
// simulated (simulateToolPathColumns, dt = 1 ms: what the page calls, its
// per-segment statistics as typed arrays) by the wasm build; the time of
// each call, the wasm memory after it (memory.buffer.byteLength, which
// only grows: the peak) and the process's peak RSS are printed, with the
// load average. SIM=objects simulates with simulateToolPath instead (one
// JS object per segment).
//   node bench/node/run.mjs large-program
//   LINES=200000 node bench/node/large-program.bench.mjs   (one size)
//   NO_CHECK=1 LINES=2000000 node bench/node/large-program.bench.mjs   (the simulation alone)
//   node bench/node/large-program.bench.mjs --write /tmp/big.nc   (the text only)
import { writeFileSync } from 'node:fs';
import { performance } from 'node:perf_hooks';

/** The program of about `lines` lines: rows of 0.2 mm chords at
 * 3,000 mm/min along a slightly slanted X with a 1 mm Z wave, every word
 * with four decimals as a finishing post writes them, joined by 0.2 mm
 * radius half-circle arcs; a comment every 500 lines and a feed change
 * every 250. About 32 bytes a line. */
export function camProgram(lines) {
  const out = ['%', 'O1000 (GENERATED FINISHING PASS)', 'N10 G21 G90 G17 G94', 'N20 T1 M6', 'N30 S12000 M3', 'N40 G0 X10. Y10. Z5.', 'N50 G1 Z0. F600.'];
  const f = (v) => v.toFixed(4).replace(/^(-?)0\./, '$1.');
  const perRow = 500;
  let x = 10;
  let y = 10;
  let dir = 1;
  let n = out.length;
  while (n < lines - 3) {
    for (let k = 0; k < perRow && n < lines - 3; k++, n++) {
      if (n % 500 === 0) {
        out.push(`(PASS ${Math.floor(n / 500)} ROW Y${f(y)})`);
        continue;
      }
      x += 0.2 * dir;
      y += 0.001;
      const z = -0.5 + 0.5 * Math.sin(x * 0.3 + y * 0.2);
      if (n % 250 === 0) out.push(`G1 X${f(x)} Y${f(y)} Z${f(z)} F${n % 1000 === 0 ? 2800 : 3000}.`);
      else out.push(`G1 X${f(x)} Y${f(y)} Z${f(z)}`);
    }
    if (n >= lines - 3) break;
    // a 0.2 mm radius half circle to the next row
    y += 0.4;
    out.push(`${dir > 0 ? 'G3' : 'G2'} X${f(x)} Y${f(y)} I0. J.2`);
    n++;
    dir = -dir;
  }
  out.push('G0 Z5.', 'M30', '%');
  return out.join('\n') + '\n';
}

const args = process.argv.slice(2);
if (args[0] === '--write') {
  writeFileSync(args[1], camProgram(Number(process.env.LINES ?? 2_000_000)));
  process.exit(0);
}

if (process.env.LINES === undefined) {
  // One fresh process per size: the wasm memory of one never shrinks.
  const { spawnSync } = await import('node:child_process');
  const { fileURLToPath } = await import('node:url');
  for (const lines of [2_000_000, 1_000_000]) {
    const r = spawnSync(process.execPath, ['--max-old-space-size=4096', fileURLToPath(import.meta.url)], { env: { ...process.env, LINES: String(lines) }, stdio: 'inherit' });
    if (r.status !== 0) console.log(`(the ${lines.toLocaleString('en')}-line run failed: status ${r.status} ${r.signal ?? ''})`);
  }
} else {
  await measure(Number(process.env.LINES));
}

async function measure(lines) {
  const { readFileSync } = await import('node:fs');
  const pkg = new URL('../../pkg/', import.meta.url);
  const wasm = await import(new URL('mtmotion.js', pkg).href);
  const exports = wasm.initSync({ module: readFileSync(new URL('mtmotion_bg.wasm', pkg)) });
  const mib = (b) => `${(b / 2 ** 20).toFixed(0)} MiB`;
  const s = (ms) => `${(ms / 1000).toFixed(2)} s`;
  // CPU time of the process (user + system) beside the wall time: on a
  // loaded machine the wall time is several times the CPU time.
  const cpu = () => { const u = process.cpuUsage(); return (u.user + u.system) / 1000; };
  let t0 = performance.now();
  const text = camProgram(lines);
  console.log(`${lines.toLocaleString('en')} lines, ${mib(text.length)} generated in ${s(performance.now() - t0)}`);

  // NO_CHECK=1: the simulation alone in a fresh module (its own peak).
  let tCheck = 0;
  if (!process.env.NO_CHECK) {
    t0 = performance.now();
    const c0 = cpu();
    const checked = wasm.checkNc(text);
    tCheck = performance.now() - t0;
    const cCheck = cpu() - c0;
    if (checked.errors.length) throw new Error(`checkNc: ${checked.errors[0].message} (line ${checked.errors[0].line})`);
    const sum = checked.summary;
    console.log(`  checkNc: ${s(tCheck)} (CPU ${s(cCheck)}); ${(sum.lines + sum.arcs + sum.rapids).toLocaleString('en')} moves, motion time ${sum.motionTime.toFixed(0)} s; wasm memory ${mib(exports.memory.buffer.byteLength)}`);
  }

  const objects = process.env.SIM === 'objects';
  const name = objects ? 'simulateToolPath' : 'simulateToolPathColumns';
  t0 = performance.now();
  const c1 = cpu();
  let sim = null;
  try {
    sim = wasm[name](text, { dt: 0.001 });
  } catch (e) {
    console.log(`  ${name} refused after ${s(performance.now() - t0)}: ${e.message}`);
  }
  const tSim = performance.now() - t0;
  const cSim = cpu() - c1;
  const stats = sim ? (objects ? sim.segments.length : sim.segmentColumns.line.length) : 0;
  if (sim) console.log(`  ${name}: ${s(tSim)} (CPU ${s(cSim)}); ${sim.samples.toLocaleString('en')} samples, max error ${sim.maxErrorUm.toFixed(1)} µm at line ${sim.maxErrorLine}, ${stats.toLocaleString('en')} segment statistics; wasm memory ${mib(exports.memory.buffer.byteLength)}`);
  const rss = process.resourceUsage().maxRSS * 1024;
  const load = (await import('node:os')).loadavg()[0].toFixed(1);
  console.log(`  check + simulate: ${s(tCheck + tSim)} (aimed at ≤ 10 s); wasm memory after both ${mib(exports.memory.buffer.byteLength)}; peak RSS ${mib(rss)} (aimed at ≤ 1 GiB); load average ${load}`);
}
