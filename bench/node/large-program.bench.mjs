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
// STREAM=1 gives the program to an NcStream instead, as ~1 MiB Uint8Array
// chunks generated as they are pushed (the whole text is never one JS
// string nor in wasm memory), then calls the stream's checkNc or
// simulateToolPathColumns; each call reads its own stream of the program,
// as each whole-text call reads the string. The time and CPU are those of
// the pushes and the finishing call, not of the generation; TOTAL=1 also
// tells the stream the text's length (new NcStream(bytes)). Without
// STREAM, every size is measured both ways (STREAM=0: the string).
//   node bench/node/run.mjs large-program
//   LINES=200000 node bench/node/large-program.bench.mjs   (one size)
//   STREAM=1 LINES=2000000 node bench/node/large-program.bench.mjs   (streamed)
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
  return [...camLines(lines)].join('\n') + '\n';
}

/** camProgram's text as UTF-8 chunks of about `bytes` bytes, each
 * generated when it is asked for (the lines of a chunk, then its bytes). */
export function* camChunks(lines, bytes = 1 << 20) {
  const encoder = new TextEncoder();
  let part = [];
  let size = 0;
  for (const line of camLines(lines)) {
    part.push(line);
    size += line.length + 1;
    if (size >= bytes) {
      yield encoder.encode(part.join('\n') + '\n');
      part = [];
      size = 0;
    }
  }
  if (part.length) yield encoder.encode(part.join('\n') + '\n');
}

/** camProgram's lines, one at a time. */
function* camLines(lines) {
  const start = ['%', 'O1000 (GENERATED FINISHING PASS)', 'N10 G21 G90 G17 G94', 'N20 T1 M6', 'N30 S12000 M3', 'N40 G0 X10. Y10. Z5.', 'N50 G1 Z0. F600.'];
  yield* start;
  const f = (v) => v.toFixed(4).replace(/^(-?)0\./, '$1.');
  const perRow = 500;
  let x = 10;
  let y = 10;
  let dir = 1;
  let n = start.length;
  while (n < lines - 3) {
    for (let k = 0; k < perRow && n < lines - 3; k++, n++) {
      if (n % 500 === 0) {
        yield `(PASS ${Math.floor(n / 500)} ROW Y${f(y)})`;
        continue;
      }
      x += 0.2 * dir;
      y += 0.001;
      const z = -0.5 + 0.5 * Math.sin(x * 0.3 + y * 0.2);
      if (n % 250 === 0) yield `G1 X${f(x)} Y${f(y)} Z${f(z)} F${n % 1000 === 0 ? 2800 : 3000}.`;
      else yield `G1 X${f(x)} Y${f(y)} Z${f(z)}`;
    }
    if (n >= lines - 3) break;
    // a 0.2 mm radius half circle to the next row
    y += 0.4;
    yield `${dir > 0 ? 'G3' : 'G2'} X${f(x)} Y${f(y)} I0. J.2`;
    n++;
    dir = -dir;
  }
  yield* ['G0 Z5.', 'M30', '%'];
}

const args = process.argv.slice(2);
if (args[0] === '--write') {
  writeFileSync(args[1], camProgram(Number(process.env.LINES ?? 2_000_000)));
  process.exit(0);
}

if (process.env.LINES === undefined) {
  // One fresh process per size and way of reading: the wasm memory of one
  // never shrinks.
  const { spawnSync } = await import('node:child_process');
  const { fileURLToPath } = await import('node:url');
  const ways = process.env.STREAM === undefined ? ['0', '1'] : [process.env.STREAM];
  for (const lines of [2_000_000, 1_000_000]) {
    for (const stream of ways) {
      const r = spawnSync(process.execPath, ['--max-old-space-size=4096', fileURLToPath(import.meta.url)], { env: { ...process.env, LINES: String(lines), STREAM: stream }, stdio: 'inherit' });
      if (r.status !== 0) console.log(`(the ${lines.toLocaleString('en')}-line run failed: status ${r.status} ${r.signal ?? ''})`);
    }
  }
} else {
  await measure(Number(process.env.LINES), process.env.STREAM === '1');
}

async function measure(lines, streamed) {
  const { readFileSync } = await import('node:fs');
  const pkg = new URL('../../pkg/', import.meta.url);
  const wasm = await import(new URL('mtmotion.js', pkg).href);
  const exports = wasm.initSync({ module: readFileSync(new URL('mtmotion_bg.wasm', pkg)) });
  const mib = (b) => `${(b / 2 ** 20).toFixed(0)} MiB`;
  const s = (ms) => `${(ms / 1000).toFixed(2)} s`;
  // CPU time of the process (user + system) beside the wall time: on a
  // loaded machine the wall time is several times the CPU time.
  const cpu = () => { const u = process.cpuUsage(); return (u.user + u.system) / 1000; };
  /** Runs `f`, adding its wall and CPU time to `t`. */
  const timed = (t, f) => {
    const w0 = performance.now();
    const c0 = cpu();
    try {
      return f();
    } finally {
      t.wall += performance.now() - w0;
      t.cpu += cpu() - c0;
    }
  };
  let call;
  let said = false;
  if (streamed) {
    // Each call reads its own stream: the chunks are generated as they are
    // pushed, outside the time measured.
    // TOTAL=1: the stream is told the text's length (as a page knows a
    // file's size), counted in a pass before, outside the time measured
    let total;
    if (process.env.TOTAL === '1') {
      total = 0;
      for (const chunk of camChunks(lines)) total += chunk.length;
    }
    call = (name, options, t) => {
      const stream = timed(t, () => new wasm.NcStream(total));
      let bytes = 0;
      for (const chunk of camChunks(lines)) {
        bytes += chunk.length;
        timed(t, () => stream.push(chunk));
      }
      if (!said) console.log(`${lines.toLocaleString('en')} lines, ${mib(bytes)} streamed in chunks of 1 MiB (NcStream${total === undefined ? '' : ', told its length'})`);
      said = true;
      return timed(t, () => stream[name](options));
    };
  } else {
    const t0 = performance.now();
    const text = camProgram(lines);
    console.log(`${lines.toLocaleString('en')} lines, ${mib(text.length)} generated in ${s(performance.now() - t0)} (one string)`);
    call = (name, options, t) => timed(t, () => wasm[name](text, options));
  }

  // NO_CHECK=1: the simulation alone in a fresh module (its own peak).
  const check = { wall: 0, cpu: 0 };
  if (!process.env.NO_CHECK) {
    const checked = call('checkNc', undefined, check);
    if (checked.errors.length) throw new Error(`checkNc: ${checked.errors[0].message} (line ${checked.errors[0].line})`);
    const sum = checked.summary;
    console.log(`  checkNc: ${s(check.wall)} (CPU ${s(check.cpu)}); ${(sum.lines + sum.arcs + sum.rapids).toLocaleString('en')} moves, motion time ${sum.motionTime.toFixed(0)} s; wasm memory ${mib(exports.memory.buffer.byteLength)}`);
  }

  const objects = process.env.SIM === 'objects';
  if (objects && streamed) throw new Error('SIM=objects: an NcStream simulates with simulateToolPathColumns only');
  const name = objects ? 'simulateToolPath' : 'simulateToolPathColumns';
  const sim = { wall: 0, cpu: 0 };
  let result = null;
  try {
    result = call(name, { dt: 0.001 }, sim);
  } catch (e) {
    console.log(`  ${name} refused after ${s(sim.wall)}: ${e.message}`);
  }
  const stats = result ? (objects ? result.segments.length : result.segmentColumns.line.length) : 0;
  if (result) console.log(`  ${name}: ${s(sim.wall)} (CPU ${s(sim.cpu)}); ${result.samples.toLocaleString('en')} samples, max error ${result.maxErrorUm.toFixed(1)} µm at line ${result.maxErrorLine}, ${stats.toLocaleString('en')} segment statistics; wasm memory ${mib(exports.memory.buffer.byteLength)}`);
  const rss = process.resourceUsage().maxRSS * 1024;
  const load = (await import('node:os')).loadavg()[0].toFixed(1);
  console.log(`  check + simulate${streamed ? ' (streamed)' : ''}: ${s(check.wall + sim.wall)} (CPU ${s(check.cpu + sim.cpu)}; aimed at ≤ 10 s); wasm memory after both ${mib(exports.memory.buffer.byteLength)}; peak RSS ${mib(rss)} (aimed at ≤ 1 GiB); load average ${load}`);
}
